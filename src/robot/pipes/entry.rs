//! Catalogue entries and classes as a sweep's values name them: an entry is one row, its size
//! and nominal weight as `pipearm pipes` prints them (`9-5/8@47.00`); a class is every row of a
//! product (`casing`).

use super::WEIGHT_MATCH_LB_FT;
use super::catalogue::{PIPE_CATALOGUE, PipeSize, Product};

/// Between a size and its nominal weight in an entry.
pub const ENTRY_SEPARATOR: char = '@';

impl PipeSize {
    /// The row as an entry: its size and nominal weight, `9-5/8@47.00`.
    pub fn entry(&self) -> String {
        format!("{}{ENTRY_SEPARATOR}{:.2}", self.size, self.nominal_weight_lb_ft)
    }
}

/// The product a class name names (`casing`, `drill-collar`: the names `payload.product` takes).
pub fn product_named(name: &str) -> Option<Product> {
    Product::ALL.into_iter().find(|p| p.name() == name)
}

/// Every row of a product, in the catalogue's order.
pub fn class_rows(product: Product) -> Vec<&'static PipeSize> {
    PIPE_CATALOGUE.iter().filter(|p| p.product == product).collect()
}

/// The row an entry names; `None` if `text` has no [`ENTRY_SEPARATOR`]; else the error says
/// what is allowed.
pub fn entry_row(text: &str) -> Option<Result<&'static PipeSize, String>> {
    let (size, weight) = text.split_once(ENTRY_SEPARATOR)?;
    let of_size: Vec<&'static PipeSize> = PIPE_CATALOGUE.iter().filter(|p| p.size == size.trim()).collect();
    if of_size.is_empty() {
        return Some(Err(format!(
            "`{text}`: no pipe size `{}` in the catalogue (`pipearm pipes` lists it)",
            size.trim()
        )));
    }
    let allowed = || of_size.iter().map(|p| p.entry()).collect::<Vec<_>>().join(", ");
    let Ok(w) = weight.trim().parse::<f64>() else {
        return Some(Err(format!("`{text}`: the weight is not a number of lb/ft: allowed {}", allowed())));
    };
    let rows: Vec<&'static PipeSize> =
        of_size.iter().copied().filter(|p| (p.nominal_weight_lb_ft - w).abs() < WEIGHT_MATCH_LB_FT).collect();
    Some(match rows.as_slice() {
        [row] => Ok(*row),
        [] => Err(format!("`{text}`: no {} pipe of {w} lb/ft: allowed {}", size.trim(), allowed())),
        // Entries are unique in the catalogue (its test); were they not, say which rows share it.
        _ => Err(format!(
            "`{text}` names {}: give payload.product",
            rows.iter().map(|p| p.label()).collect::<Vec<_>>().join(", ")
        )),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_entry_names_one_row_and_reads_back_to_it() {
        for p in PIPE_CATALOGUE {
            let same: Vec<_> = PIPE_CATALOGUE.iter().filter(|q| q.entry() == p.entry()).collect();
            assert_eq!(same.len(), 1, "{} is not unique", p.entry());
            assert_eq!(entry_row(&p.entry()).unwrap().unwrap(), p);
        }
        assert_eq!(entry_row("9-5/8@47").unwrap().unwrap().entry(), "9-5/8@47.00");
        assert!(entry_row("9-5/8").is_none());
        assert!(entry_row("9-5/8@48").unwrap().unwrap_err().contains("9-5/8@47.00"));
        assert!(entry_row("9-7/8@47").unwrap().unwrap_err().contains("pipearm pipes"));
    }
}
