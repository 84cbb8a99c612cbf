//! Seeded sample designs on the unit hypercube: Latin hypercube samples, and Saltelli's design for
//! Sobol indices built from them. A design's unit samples `u ∈ (0, 1)` become key values through
//! each key's [`Distribution::quantile`](super::dist::Distribution::quantile).
//!
//! Reproducibility: every number comes from one ChaCha8 stream (`ChaCha8Rng::seed_from_u64(seed)`),
//! a specified cipher, and is turned into an integer or a float by the code here rather than by
//! `rand`'s distributions, so the same seed gives the same bytes on every platform and release. A
//! design is built whole before any run, so threads and shards see the same rows.

use rand::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `samples` Latin hypercube samples of `dimensions` unit coordinates: `rows[i][d] ∈ (0, 1)`.
///
/// Each dimension is cut into `samples` equal strata; a random permutation assigns one stratum to
/// each sample (independently per dimension) and a uniform jitter places the sample inside it, so
/// every stratum `⌊u·samples⌋` of every dimension holds exactly one sample. Stream order: for each
/// dimension in turn, the permutation's draws (Fisher–Yates) then the `samples` jitters.
pub fn latin_hypercube(samples: usize, dimensions: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = stream(seed);
    let mut rows = vec![vec![0.0; dimensions]; samples];
    for d in 0..dimensions {
        let strata = permutation(&mut rng, samples);
        for (row, &stratum) in rows.iter_mut().zip(&strata) {
            row[d] = in_stratum(stratum, samples, open_unit(&mut rng));
        }
    }
    rows
}

/// Saltelli's sample design for Sobol indices of `dimensions` inputs with `base` rows per matrix.
///
/// A and B are the two halves of one Latin hypercube of 2k dimensions (A its first k columns, B its
/// last k): every column has its own independent permutation, so A and B are independent as the
/// estimators require, each is a Latin hypercube in its own right, and one seed fixes both. AB_i is
/// A with column i taken from B.
#[derive(Debug, Clone, PartialEq)]
pub struct SaltelliDesign {
    /// Rows per matrix (N).
    pub base: usize,
    /// Number of inputs (k).
    pub dimensions: usize,
    /// The N(k + 2) unit samples in the order A, B, AB_0, ..., AB_{k−1}, N rows each.
    pub rows: Vec<Vec<f64>>,
}

/// Builds the [`SaltelliDesign`] of `base` rows per matrix for `dimensions` inputs.
pub fn saltelli(base: usize, dimensions: usize, seed: u64) -> SaltelliDesign {
    let joint = latin_hypercube(base, 2 * dimensions, seed);
    let a = joint.iter().map(|row| row[..dimensions].to_vec());
    let b = joint.iter().map(|row| row[dimensions..].to_vec());
    let mut rows: Vec<Vec<f64>> = a.chain(b).collect();
    for i in 0..dimensions {
        rows.extend(joint.iter().map(|row| {
            let mut ab = row[..dimensions].to_vec();
            ab[i] = row[dimensions + i];
            ab
        }));
    }
    SaltelliDesign { base, dimensions, rows }
}

impl SaltelliDesign {
    /// Number of runs the design needs: N(k + 2).
    pub fn runs(&self) -> usize {
        self.base * (self.dimensions + 2)
    }

    /// The results of the A rows out of `y` (one result per row, in the design's order).
    ///
    /// # Panics
    /// If `y` does not hold one result per row.
    pub fn y_a<'y>(&self, y: &'y [f64]) -> &'y [f64] {
        self.block(y, 0)
    }

    /// The results of the B rows out of `y`.
    ///
    /// # Panics
    /// If `y` does not hold one result per row.
    pub fn y_b<'y>(&self, y: &'y [f64]) -> &'y [f64] {
        self.block(y, 1)
    }

    /// The results of the AB_i rows (A with column `i` from B) out of `y`.
    ///
    /// # Panics
    /// If `y` does not hold one result per row, or `i` ≥ k.
    pub fn y_ab<'y>(&self, y: &'y [f64], i: usize) -> &'y [f64] {
        assert!(i < self.dimensions, "input {i} of a design with {} inputs", self.dimensions);
        self.block(y, 2 + i)
    }

    fn block<'y>(&self, y: &'y [f64], index: usize) -> &'y [f64] {
        assert_eq!(y.len(), self.runs(), "one result per design row");
        &y[index * self.base..(index + 1) * self.base]
    }
}

/// The random stream of `seed`.
pub(super) fn stream(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A uniformly random permutation of 0..n (Fisher–Yates, from the top down).
fn permutation(rng: &mut ChaCha8Rng, n: usize) -> Vec<usize> {
    let mut p: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        p.swap(i, below(rng, i as u64 + 1) as usize);
    }
    p
}

/// A uniform integer in 0..n (n > 0), unbiased by rejecting the incomplete last block of u64.
pub(super) fn below(rng: &mut ChaCha8Rng, n: u64) -> u64 {
    let limit = u64::MAX - u64::MAX % n;
    loop {
        let x = rng.next_u64();
        if x < limit {
            return x % n;
        }
    }
}

/// A uniform float in the open interval (0, 1): the midpoint of one of 2⁵³ equal cells.
fn open_unit(rng: &mut ChaCha8Rng) -> f64 {
    ((rng.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
}

/// The point at fraction `jitter` of stratum `k` of `n`, nudged by an ulp where rounding would put
/// it in a neighbouring stratum or on 0 or 1.
fn in_stratum(k: usize, n: usize, jitter: f64) -> f64 {
    let mut u = (k as f64 + jitter) / n as f64;
    let stratum = |u: f64| (u * n as f64).floor();
    while stratum(u) < k as f64 || u <= 0.0 {
        u = u.next_up();
    }
    while stratum(u) > k as f64 || u >= 1.0 {
        u = u.next_down();
    }
    u
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every dimension has exactly one sample in each stratum ⌊u·n⌋, and every u is in (0, 1).
    fn assert_stratified(rows: &[Vec<f64>], n: usize, k: usize) {
        assert_eq!(rows.len(), n);
        for d in 0..k {
            let mut count = vec![0; n];
            for row in rows {
                assert_eq!(row.len(), k);
                let u = row[d];
                assert!(u > 0.0 && u < 1.0, "u = {u}");
                count[(u * n as f64).floor() as usize] += 1;
            }
            assert!(count.iter().all(|&c| c == 1), "dimension {d} of n = {n}: strata counts {count:?}");
        }
    }

    #[test]
    fn latin_hypercube_has_one_sample_per_stratum() {
        for (n, k, seed) in [(1, 1, 0), (2, 3, 1), (10, 4, 42), (97, 6, 7), (1000, 3, 123_456_789), (3, 2, u64::MAX)] {
            assert_stratified(&latin_hypercube(n, k, seed), n, k);
        }
    }

    #[test]
    fn latin_hypercube_is_reproducible_and_seed_dependent() {
        let bytes = |rows: Vec<Vec<f64>>| rows.iter().flatten().flat_map(|u| u.to_le_bytes()).collect::<Vec<u8>>();
        assert_eq!(bytes(latin_hypercube(50, 5, 9)), bytes(latin_hypercube(50, 5, 9)));
        assert_ne!(bytes(latin_hypercube(50, 5, 9)), bytes(latin_hypercube(50, 5, 10)));
        // Dimensions are not copies of each other.
        let rows = latin_hypercube(50, 2, 9);
        assert!(rows.iter().any(|r| (r[0] * 50.0).floor() != (r[1] * 50.0).floor()));
    }

    #[test]
    fn latin_hypercube_is_uniform_on_average() {
        // One point per stratum puts the mean within 1/(2n) of ½ (each point within half a stratum
        // of its stratum's centre, and the centres average ½).
        let rows = latin_hypercube(400, 3, 5);
        for d in 0..3 {
            let mean = rows.iter().map(|r| r[d]).sum::<f64>() / 400.0;
            assert!((mean - 0.5).abs() <= 0.5 / 400.0, "dimension {d}: mean {mean}");
        }
    }

    #[test]
    fn in_stratum_keeps_edge_points_inside() {
        // A jitter of 1 − 2⁻⁵⁴ in the top stratum rounds (k + j)/n to 1.0 without the nudge.
        let top = in_stratum(2, 3, 1.0 - f64::EPSILON / 4.0);
        assert!(top < 1.0 && (top * 3.0).floor() == 2.0);
        let bottom = in_stratum(0, 3, f64::MIN_POSITIVE);
        assert!(bottom > 0.0);
    }

    #[test]
    fn saltelli_design_layout() {
        let (n, k) = (16, 3);
        let design = saltelli(n, k, 11);
        assert_eq!(design.rows.len(), n * (k + 2));
        assert_eq!(design.runs(), n * (k + 2));
        let (a, b) = (&design.rows[..n], &design.rows[n..2 * n]);
        assert_stratified(a, n, k);
        assert_stratified(b, n, k);
        for i in 0..k {
            let ab = &design.rows[(2 + i) * n..(3 + i) * n];
            for j in 0..n {
                for c in 0..k {
                    let expected = if c == i { b[j][c] } else { a[j][c] };
                    assert_eq!(ab[j][c], expected, "AB_{i} row {j} column {c}");
                }
            }
        }
        // The accessors split a result vector in the same order.
        let y: Vec<f64> = (0..design.runs()).map(|r| r as f64).collect();
        assert_eq!(design.y_a(&y)[0], 0.0);
        assert_eq!(design.y_b(&y)[0], n as f64);
        assert_eq!(design.y_ab(&y, 2)[n - 1], (4 * n + n - 1) as f64);
        assert_eq!(saltelli(n, k, 11), design);
    }
}
