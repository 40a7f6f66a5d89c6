//! `view --clock frames|real`: the camera follows the scene's path, as in `bench`, instead of
//! the fly camera. `frames` shows one step of the path per frame (the paper's protocol:
//! motion slows down when frames do); `real` shows the path at each frame's predicted display
//! time, as `bench --clock real` does: the window's time plus the last frame interval (with
//! vsync and two buffers a frame started now is shown about one interval later).

use crate::cli::ClockChoice;
use steadyray_scene::{Camera, CameraPath};

/// Where on the scene's path the next frame is.
#[derive(Clone, Debug)]
pub struct PathClock {
    choice: ClockChoice,
    path: CameraPath,
    /// The scene's camera: the eye, pitch and field of view the path starts from.
    base: Camera,
    /// Frames shown (frame clock).
    frame: u32,
    /// Path time shown, s (real clock; stops while paused).
    elapsed_s: f64,
}

impl PathClock {
    /// A clock at the path's start.
    pub fn new(choice: ClockChoice, path: CameraPath, base: Camera) -> Self {
        Self {
            choice,
            path,
            base,
            frame: 0,
            elapsed_s: 0.0,
        }
    }

    /// The camera and scene time of the next frame; `interval_s` is the window time since
    /// the previous frame began. While `paused` the path stands still.
    pub fn next(&mut self, interval_s: f64, paused: bool) -> (Camera, f64) {
        match self.choice {
            ClockChoice::Frames => {
                let n = self.path.frames().max(1);
                let k = self.frame % n;
                if !paused {
                    self.frame = self.frame.wrapping_add(1);
                }
                (
                    self.path.camera(&self.base, k, n),
                    self.path.frame_time(k, n),
                )
            }
            ClockChoice::Real => {
                let ahead = if paused {
                    0.0
                } else {
                    self.elapsed_s += interval_s;
                    interval_s
                };
                let t = self.elapsed_s + ahead;
                (self.path.camera_at_time(&self.base, t), t)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn corridor() -> (CameraPath, Camera) {
        let scene = steadyray_scene::builtin("corridor").unwrap();
        (scene.path, scene.camera)
    }

    #[test]
    fn the_frame_clock_steps_the_path_once_a_frame() {
        let (path, base) = corridor();
        let mut clock = PathClock::new(ClockChoice::Frames, path.clone(), base);
        let n = path.frames();
        for k in 0..3 {
            let (camera, t) = clock.next(0.5, false);
            assert_eq!(camera.forward, path.camera(&base, k, n).forward);
            assert_eq!(t, path.frame_time(k, n));
        }
        let (_, t) = clock.next(0.5, true);
        assert_eq!(t, path.frame_time(3, n));
        let (_, again) = clock.next(0.5, false);
        assert_eq!(again, t, "a paused frame does not advance the path");
    }

    #[test]
    fn the_real_clock_shows_the_predicted_display_time() {
        let (path, base) = corridor();
        let mut clock = PathClock::new(ClockChoice::Real, path.clone(), base);
        let (_, t0) = clock.next(0.0, false);
        assert_eq!(t0, 0.0);
        // 20 ms frames: the frame started at 20 ms is shown one interval later, at 40 ms.
        let (camera, t1) = clock.next(0.02, false);
        assert!((t1 - 0.04).abs() < 1e-12);
        assert!((camera.forward - path.camera_at_time(&base, 0.04).forward).length() < 1e-6);
        let (_, paused) = clock.next(0.02, true);
        assert!(
            (paused - 0.02).abs() < 1e-12,
            "paused: the time shown stands at the clock"
        );
    }
}
