//! `pipearm pipes [FILTER]...`: the pipe catalogue.

use anyhow::{Result, bail};
use clap::Args;

use pipearm::robot::pipes::{PIPE_CATALOGUE, PipeSize, Product, entry_row};

/// `pipearm pipes`' arguments.
#[derive(Args)]
#[command(after_help = super::help::PIPES)]
pub struct PipesArgs {
    /// Sizes (9-5/8), entries (9-5/8@47.00) or products (casing, tubing, drill-pipe,
    /// heavy-weight-drill-pipe, drill-collar) a row must match, all of them.
    pub filters: Vec<String>,
}

/// Prints the catalogue rows every filter matches (a size such as `9-5/8`, an entry such as
/// `9-5/8@47.00`, or a product such as `casing`).
pub fn pipes(filters: &[String]) -> Result<()> {
    let mut entries: Vec<&PipeSize> = Vec::new();
    for f in filters {
        if let Some(row) = entry_row(f) {
            entries.push(row.map_err(anyhow::Error::msg)?);
            continue;
        }
        let known = PIPE_CATALOGUE.iter().any(|p| p.size == f) || Product::ALL.iter().any(|p| p.name() == f);
        if !known {
            let products: Vec<&str> = Product::ALL.iter().map(|p| p.name()).collect();
            bail!(
                "`{f}` is neither a size, an entry nor a product of the catalogue: allowed a size (2-3/8, 9-5/8, ...), \
                 an entry SIZE@LB_FT (9-5/8@47.00) or {}",
                products.join(", ")
            );
        }
    }
    let matches = |p: &PipeSize| {
        entries.iter().all(|e| *e == p)
            && filters.iter().filter(|f| entry_row(f).is_none()).all(|f| p.size == f || p.product.name() == f)
    };
    println!(
        "{:<24} {:>13} {:>7} {:>7} {:>7} {:>7}  {:<20} {:>7}  {:>14} {:>14} {:>14}",
        "product",
        "size@lb/ft",
        "OD mm",
        "wall mm",
        "kg/m",
        "pe kg/m",
        "connection",
        "conn kg",
        "R1 kg @ m",
        "R2 kg @ m",
        "R3 kg @ m"
    );
    for p in PIPE_CATALOGUE.iter().filter(|p| matches(p)) {
        let joints: Vec<String> = p
            .product
            .ranges()
            .iter()
            .map(|r| r.map_or("-".into(), |r| format!("{:.1} @ {:.2}", p.joint_mass_kg(r.default_m), r.default_m)))
            .collect();
        let c = &p.connection;
        let conn_kg = if c.is_integral() {
            "-".to_string()
        } else {
            format!("{:.1}{}", c.added_mass_kg, if c.mass_published { "" } else { "*" })
        };
        println!(
            "{:<24} {:>13} {:>7.1} {:>7.2} {:>7.2} {:>7.2}  {:<20} {:>7}  {:>14} {:>14} {:>14}{}",
            p.product.name(),
            p.entry(),
            1e3 * p.outer_diameter_m,
            1e3 * p.wall_m,
            p.mass_per_length_kg_m,
            p.plain_end_kg_m(),
            c.name,
            conn_kg,
            joints[0],
            joints[1],
            joints[2],
            if p.default { "  (default)" } else { "" }
        );
    }
    println!(
        "pe: plain end; * estimated connection mass (docs/pipes.md); joint: plain pipe + connection at the range's default length"
    );
    Ok(())
}
