//! Shards: shard `I` of `N` runs the cases with `index % N == I`. The index comes from
//! `--shard I/N`, or with `--shard-count N` from the batch engine: Slurm job arrays set
//! `SLURM_ARRAY_TASK_ID`, Kubernetes Indexed Jobs `JOB_COMPLETION_INDEX`.

use super::SweepError;

/// Environment variables that carry a task's index, in the order they are read.
pub const INDEX_VARIABLES: [&str; 2] = ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"];

/// One shard of a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// Which shard, from 0.
    pub index: usize,
    /// How many shards.
    pub count: usize,
}

impl Shard {
    /// The whole sweep as one shard.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// A checked shard `index` of `count`.
    pub fn new(index: usize, count: usize) -> Result<Shard, SweepError> {
        if count == 0 || index >= count {
            return Err(SweepError::Shard(format!("index {index} of {count} shards: allowed 0 <= I < N, N >= 1")));
        }
        Ok(Shard { index, count })
    }

    /// Shard `count` with its index from the first of [`INDEX_VARIABLES`] that `lookup` finds.
    pub fn from_env(count: usize, lookup: impl Fn(&str) -> Option<String>) -> Result<Shard, SweepError> {
        let (name, text) = INDEX_VARIABLES.iter().find_map(|n| lookup(n).map(|v| (n, v))).ok_or_else(|| {
            SweepError::Shard(format!(
                "--shard-count {count} without --shard needs the task index in {}; neither is set",
                INDEX_VARIABLES.join(" or ")
            ))
        })?;
        let index = text.trim().parse().map_err(|_| SweepError::Shard(format!("{name} = `{text}` is not an index")))?;
        Shard::new(index, count).map_err(|e| SweepError::Shard(format!("{name}: {e}")))
    }

    /// Whether case `index` belongs to this shard.
    pub fn contains(&self, case_index: usize) -> bool {
        case_index % self.count == self.index
    }
}

impl std::str::FromStr for Shard {
    type Err = SweepError;

    /// `I/N`, 0-based.
    fn from_str(text: &str) -> Result<Shard, SweepError> {
        let bad = || SweepError::Shard(format!("`{text}`: allowed I/N with 0 <= I < N, e.g. 0/3"));
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let (i, n) = (i.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
        Shard::new(i, n).map_err(|_| bad())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_split_the_cases_round_robin() {
        let s: Shard = "1/3".parse().unwrap();
        assert_eq!((0..9).filter(|i| s.contains(*i)).collect::<Vec<_>>(), [1, 4, 7]);
        assert!("3/3".parse::<Shard>().is_err() && "x/3".parse::<Shard>().is_err() && "0/0".parse::<Shard>().is_err());
    }

    #[test]
    fn the_index_comes_from_slurm_then_kubernetes() {
        let env = |vars: &'static [(&'static str, &'static str)]| {
            move |n: &str| vars.iter().find(|(k, _)| *k == n).map(|(_, v)| v.to_string())
        };
        let both = env(&[("JOB_COMPLETION_INDEX", "2"), ("SLURM_ARRAY_TASK_ID", "1")]);
        assert_eq!(Shard::from_env(3, both).unwrap(), Shard { index: 1, count: 3 });
        assert_eq!(Shard::from_env(3, env(&[("JOB_COMPLETION_INDEX", "2")])).unwrap().index, 2);
        assert!(Shard::from_env(3, env(&[])).unwrap_err().to_string().contains("SLURM_ARRAY_TASK_ID"));
        assert!(Shard::from_env(3, env(&[("SLURM_ARRAY_TASK_ID", "3")])).is_err());
    }
}
