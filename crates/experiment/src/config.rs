//! The settings several of the experiment's commands share: the scene and its renderer, the
//! quality bounds, the display, the clock and the temporal mode. Plain values: the command
//! line (or any other caller) fills them in.

use serde::Serialize;

/// Which renderer backend to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BackendChoice {
    /// A real GPU (discrete or integrated) if there is one, else the CPU renderer.
    Auto,
    /// The wgpu compute renderer on any adapter, software ones (lavapipe) included.
    Gpu,
    /// The CPU reference renderer.
    Cpu,
}

/// A camera path put in place of the scene's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathChoice {
    /// The paper's sweep: one full turn of the yaw at constant speed.
    Sweep,
    /// Holds, slow pans and fast turns (one full turn in 8 s): motion on screen from 0 to
    /// about 100 degrees of visual angle per second (docs/scene-format.md).
    Pans,
}

/// The scene to render and the renderer to render it with.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneConfig {
    /// A built-in scene name or a scene file (.toml).
    pub scene: String,
    /// Renderer backend.
    pub backend: BackendChoice,
    /// Replaces the scene's camera path (keeping its frame count), from the scene camera's
    /// eye and pitch.
    pub path: Option<PathChoice>,
}

impl Default for SceneConfig {
    /// The default scene on the default backend, on its own camera path.
    fn default() -> Self {
        Self {
            scene: steadyray_scene::DEFAULT_SCENE.to_string(),
            backend: BackendChoice::Auto,
            path: None,
        }
    }
}

impl SceneConfig {
    /// Loads the scene and puts `path` in place of its camera path.
    pub fn load(&self) -> Result<steadyray_scene::Scene, steadyray_scene::SceneError> {
        use steadyray_scene::CameraPath;
        let mut scene = steadyray_scene::load_scene(&self.scene)?;
        let frames = scene.path.frames();
        match self.path {
            Some(PathChoice::Sweep) => scene.path = CameraPath::sweep(frames),
            Some(PathChoice::Pans) => scene.path = CameraPath::pans(frames),
            None => {}
        }
        Ok(scene)
    }
}

/// How time runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClockChoice {
    /// The paper's protocol: frame k of N shows the path at k/N of its length, whatever its
    /// time.
    Frames,
    /// Display time: the path is a function of time and each frame shows the world at its
    /// predicted display time, so a faster controller shows more frames of the same motion.
    Real,
}

/// Which runs use the temporal mode (`docs/temporal.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TemporalChoice {
    /// None.
    Off,
    /// Every run.
    On,
    /// Every controller runs twice: without, then with it.
    Both,
}

impl TemporalChoice {
    /// The modes each controller runs in, in order (false: without it).
    pub fn modes(self) -> &'static [bool] {
        match self {
            TemporalChoice::Off => &[false],
            TemporalChoice::On => &[true],
            TemporalChoice::Both => &[false, true],
        }
    }
}

/// The display model's settings under the real clock, as given: [`DisplaySettings::config`]
/// checks them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DisplaySettings {
    /// The display's refresh rate, Hz (default 60; with `vrr`, the range's maximum).
    pub refresh: Option<f64>,
    /// Vsync on (a frame shows at the first refresh after it is complete; the default) or
    /// off (at once).
    pub vsync: Option<bool>,
    /// Variable refresh within a range instead of a fixed refresh.
    pub vrr: Option<steadyray_display::VrrRange>,
}

impl DisplaySettings {
    /// Whether any display setting was given.
    pub fn is_given(&self) -> bool {
        self.refresh.is_some() || self.vsync.is_some() || self.vrr.is_some()
    }

    /// The checked display.
    pub fn config(
        &self,
    ) -> Result<steadyray_display::DisplayConfig, steadyray_display::DisplayError> {
        use steadyray_display::{DisplayConfig, SyncMode};
        let sync = match (self.vrr, self.vsync) {
            (Some(range), _) => SyncMode::Vrr(range),
            (None, Some(false)) => SyncMode::Off,
            (None, _) => SyncMode::Vsync,
        };
        let refresh = self.refresh.unwrap_or(self.vrr.map_or(60.0, |r| r.max_hz));
        DisplayConfig::new(refresh, sync)
    }
}
