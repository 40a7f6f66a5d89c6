//! The written form of a display-aligned band, `refresh` or `refresh:M`.

/// `refresh[:M]` (`bench --band`, `view --band`): a band for frames shown every M-th refresh,
/// which [`crate::aligned_band`] derives from the display and the measured costs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RefreshBand {
    /// Frames are shown every this many refreshes (at least 1).
    pub multiple: u32,
}

impl std::str::FromStr for RefreshBand {
    type Err = String;

    fn from_str(text: &str) -> std::result::Result<Self, Self::Err> {
        let bad = || format!("`{text}`: write refresh, or refresh:M with M a whole number >= 1");
        let multiple = match text.trim().split_once(':') {
            None if text.trim() == "refresh" => 1,
            Some(("refresh", m)) => m.trim().parse::<u32>().map_err(|_| bad())?,
            _ => return Err(bad()),
        };
        if multiple == 0 {
            return Err(bad());
        }
        Ok(Self { multiple })
    }
}

impl std::fmt::Display for RefreshBand {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.multiple {
            1 => write!(f, "refresh"),
            m => write!(f, "refresh:{m}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refresh_bands_parse() {
        assert_eq!("refresh".parse(), Ok(RefreshBand { multiple: 1 }));
        assert_eq!("refresh:2".parse(), Ok(RefreshBand { multiple: 2 }));
        for bad in ["refresh:0", "refresh:x", "vsync", "refresh:"] {
            let err = bad.parse::<RefreshBand>().unwrap_err();
            assert!(err.contains("refresh:M"), "{bad}: {err}");
        }
        assert_eq!(RefreshBand { multiple: 2 }.to_string(), "refresh:2");
    }
}
