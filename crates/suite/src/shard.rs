//! Shards: the I-th of N slices of the suite's cells, so that N machines (a Slurm job array,
//! any batch system) each run a slice and a merge joins their results.

use crate::error::SuiteError;
use std::fmt;
use std::str::FromStr;

/// The `index`-th (1-based) of `count` slices. Cell number p of the plan belongs to slice
/// p mod count + 1, so every slice holds every scene and method in turn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    index: u32,
    count: u32,
}

impl Shard {
    /// All the cells (1/1).
    pub const ALL: Shard = Shard { index: 1, count: 1 };

    /// The `index`-th of `count` slices (1 ≤ index ≤ count).
    pub fn new(index: u32, count: u32) -> Result<Self, SuiteError> {
        if count == 0 || index == 0 || index > count {
            return Err(SuiteError::BadShard(format!("{index}/{count}")));
        }
        Ok(Self { index, count })
    }

    /// Whether the cell at `position` in the plan's order is this slice's.
    pub fn takes(&self, position: usize) -> bool {
        position % self.count as usize == (self.index - 1) as usize
    }
}

impl FromStr for Shard {
    type Err = SuiteError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let bad = || SuiteError::BadShard(text.to_string());
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let parse = |s: &str| s.trim().parse::<u32>().map_err(|_| bad());
        Shard::new(parse(i)?, parse(n)?).map_err(|_| bad())
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_refuses() {
        assert_eq!("2/4".parse::<Shard>().unwrap(), Shard::new(2, 4).unwrap());
        for bad in ["0/4", "5/4", "1/0", "2", "a/b", "1/2/3", ""] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }

    #[test]
    fn the_slices_cover_every_cell_once() {
        let shards: Vec<Shard> = (1..=3).map(|i| Shard::new(i, 3).unwrap()).collect();
        for position in 0..20 {
            assert_eq!(shards.iter().filter(|s| s.takes(position)).count(), 1);
        }
    }
}
