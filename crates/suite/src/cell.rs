//! A cell: one method on one scene, one run; and what its run measured.

use serde::{Deserialize, Serialize};

/// One job of the suite: method `method` on scene `scene`, run `run` (0-based).
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct Cell {
    /// The scene's name.
    pub scene: String,
    /// The method's name.
    pub method: String,
    /// Which of the K runs.
    pub run: u32,
}

impl Cell {
    /// The cell's id and folder, relative to the suite's folder: `scene/method/run-k`.
    pub fn id(&self) -> String {
        format!("{}/{}/run-{}", self.scene, self.method, self.run)
    }
}

/// What a cell's run measured: the figures the table ranks by and those it shows beside.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CellResult {
    /// The cell.
    pub cell: Cell,
    /// Displayed FLIP: the screen against the world at the sampled refreshes (lower is
    /// better).
    pub displayed_flip: f64,
    /// ColorVideoVDP's JOD of the screen video (10 = indistinguishable from the reference),
    /// where it was scored.
    pub jod: Option<f64>,
    /// Frames shown per second.
    pub displayed_fps: f64,
    /// Frames whose time fell in the method's band, %.
    pub in_band_pct: f64,
    /// Seconds the cell took, all of it (with the calibration of its scene's `perceptual`
    /// model for the first `perceptual-scene` cell, which needs one).
    pub seconds: f64,
}
