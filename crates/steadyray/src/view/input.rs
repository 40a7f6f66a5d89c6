//! Keyboard and mouse input of the view as plain state, testable without a window: which
//! keys do what, which movement keys are held, and the mouse-look drag.

use glam::Vec3;
use winit::keyboard::KeyCode;

/// A movement direction in the camera's frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MoveKey {
    Forward,
    Back,
    Left,
    Right,
    Up,
    Down,
}

impl MoveKey {
    const ALL: [MoveKey; 6] = [
        MoveKey::Forward,
        MoveKey::Back,
        MoveKey::Left,
        MoveKey::Right,
        MoveKey::Up,
        MoveKey::Down,
    ];

    /// The direction in camera space: x right, y up, z forward.
    fn direction(self) -> Vec3 {
        match self {
            MoveKey::Forward => Vec3::Z,
            MoveKey::Back => Vec3::NEG_Z,
            MoveKey::Left => Vec3::NEG_X,
            MoveKey::Right => Vec3::X,
            MoveKey::Up => Vec3::Y,
            MoveKey::Down => Vec3::NEG_Y,
        }
    }
}

/// A one-shot command a key press gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// F1: show or hide the HUD.
    ToggleHud,
    /// Space: start or stop the automatic sweep.
    ToggleSweep,
    /// P: freeze or resume the camera (and playback).
    TogglePause,
    /// T: turn the temporal mode on or off.
    ToggleTemporal,
    /// V: show the refreshes between frames warped or repeat the frame (`--warp`).
    ToggleWarps,
    /// F12: save a screenshot PNG.
    Screenshot,
    /// Escape: close the view.
    Quit,
}

/// What a key does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Binding {
    Move(MoveKey),
    Command(Command),
}

/// WASD moves in the view plane, Q/E down and up; the commands as in [`Command`].
fn binding(code: KeyCode) -> Option<Binding> {
    use Binding::{Command as C, Move as M};
    Some(match code {
        KeyCode::KeyW => M(MoveKey::Forward),
        KeyCode::KeyS => M(MoveKey::Back),
        KeyCode::KeyA => M(MoveKey::Left),
        KeyCode::KeyD => M(MoveKey::Right),
        KeyCode::KeyE => M(MoveKey::Up),
        KeyCode::KeyQ => M(MoveKey::Down),
        KeyCode::F1 => C(Command::ToggleHud),
        KeyCode::Space => C(Command::ToggleSweep),
        KeyCode::KeyP => C(Command::TogglePause),
        KeyCode::KeyT => C(Command::ToggleTemporal),
        KeyCode::KeyV => C(Command::ToggleWarps),
        KeyCode::F12 => C(Command::Screenshot),
        KeyCode::Escape => C(Command::Quit),
        _ => return None,
    })
}

/// Radians of camera turn per pixel of mouse drag.
pub const LOOK_RADIANS_PER_PIXEL: f32 = 0.004;

/// Held movement keys and the mouse-look drag.
#[derive(Clone, Debug, Default)]
pub struct InputState {
    held: [bool; 6],
    dragging: bool,
    last_cursor: Option<(f64, f64)>,
    /// Cursor travel while dragging since the last [`Self::take_look`], pixels.
    look: (f64, f64),
}

impl InputState {
    /// Takes a key event; returns the command of a first press (never of a repeat or release).
    pub fn key(&mut self, code: KeyCode, pressed: bool, repeat: bool) -> Option<Command> {
        match binding(code)? {
            Binding::Move(key) => {
                self.held[key as usize] = pressed;
                None
            }
            Binding::Command(command) => (pressed && !repeat).then_some(command),
        }
    }

    /// A mouse button that turns the camera while held went down or up.
    pub fn look_button(&mut self, pressed: bool) {
        self.dragging = pressed;
    }

    /// The cursor moved to `(x, y)` (window pixels).
    pub fn cursor_moved(&mut self, x: f64, y: f64) {
        if let (true, Some((px, py))) = (self.dragging, self.last_cursor) {
            self.look.0 += x - px;
            self.look.1 += y - py;
        }
        self.last_cursor = Some((x, y));
    }

    /// The cursor left the window: stop turning (the release may never arrive).
    pub fn cursor_left(&mut self) {
        self.dragging = false;
        self.last_cursor = None;
    }

    /// The focus moved away: forget held keys and the drag.
    pub fn focus_lost(&mut self) {
        *self = Self::default();
    }

    /// (yaw, pitch) change in radians for the drag since the last call: dragging right turns
    /// right, dragging up looks up.
    pub fn take_look(&mut self) -> (f32, f32) {
        let (dx, dy) = std::mem::take(&mut self.look);
        (
            dx as f32 * LOOK_RADIANS_PER_PIXEL,
            -dy as f32 * LOOK_RADIANS_PER_PIXEL,
        )
    }

    /// The held movement as a camera-space vector (x right, y up, z forward), unit length
    /// or zero.
    pub fn movement(&self) -> Vec3 {
        MoveKey::ALL
            .iter()
            .filter(|&&k| self.held[k as usize])
            .map(|k| k.direction())
            .sum::<Vec3>()
            .normalize_or_zero()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commands_fire_once_per_press() {
        let mut input = InputState::default();
        assert_eq!(
            input.key(KeyCode::F1, true, false),
            Some(Command::ToggleHud)
        );
        assert_eq!(input.key(KeyCode::F1, true, true), None, "repeat");
        assert_eq!(input.key(KeyCode::F1, false, false), None, "release");
        assert_eq!(
            input.key(KeyCode::Space, true, false),
            Some(Command::ToggleSweep)
        );
        assert_eq!(
            input.key(KeyCode::KeyP, true, false),
            Some(Command::TogglePause)
        );
        assert_eq!(
            input.key(KeyCode::F12, true, false),
            Some(Command::Screenshot)
        );
        assert_eq!(input.key(KeyCode::KeyZ, true, false), None);
    }

    #[test]
    fn held_keys_combine_into_a_unit_direction() {
        let mut input = InputState::default();
        assert_eq!(input.movement(), Vec3::ZERO);
        input.key(KeyCode::KeyW, true, false);
        assert_eq!(input.movement(), Vec3::Z);
        input.key(KeyCode::KeyD, true, false);
        let m = input.movement();
        assert!(
            (m.length() - 1.0).abs() < 1e-6 && m.x > 0.0 && m.z > 0.0,
            "{m}"
        );
        input.key(KeyCode::KeyS, true, false);
        assert_eq!(input.movement(), Vec3::X, "forward and back cancel");
        input.key(KeyCode::KeyW, false, false);
        input.key(KeyCode::KeyS, false, false);
        input.key(KeyCode::KeyD, false, false);
        input.key(KeyCode::KeyE, true, false);
        assert_eq!(input.movement(), Vec3::Y);
        input.focus_lost();
        assert_eq!(input.movement(), Vec3::ZERO);
    }

    #[test]
    fn only_a_drag_turns_the_camera() {
        let mut input = InputState::default();
        input.cursor_moved(10.0, 10.0);
        input.cursor_moved(50.0, 10.0);
        assert_eq!(input.take_look(), (0.0, 0.0), "no button held");
        input.look_button(true);
        input.cursor_moved(60.0, 0.0);
        input.cursor_moved(70.0, 0.0);
        let (yaw, pitch) = input.take_look();
        assert!((yaw - 20.0 * LOOK_RADIANS_PER_PIXEL).abs() < 1e-6);
        assert!(
            (pitch - 10.0 * LOOK_RADIANS_PER_PIXEL).abs() < 1e-6,
            "up looks up"
        );
        assert_eq!(input.take_look(), (0.0, 0.0), "taken");
        input.look_button(false);
        input.cursor_moved(0.0, 0.0);
        assert_eq!(input.take_look(), (0.0, 0.0));
    }
}
