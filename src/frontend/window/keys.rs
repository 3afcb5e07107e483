//! Window input to viewer input: movement keys, Shift / Ctrl and the left-button mouse drag
//! fill the fly camera's [`FlyInput`]; other key presses map to viewer [`Action`]s.

use super::fly_camera::FlyInput;
use crate::frontend::view_state::Action;
use winit::keyboard::{KeyCode, ModifiersState};

/// The viewer command of a key press (movement keys are held state, not commands).
pub fn action(key: KeyCode, mods: ModifiersState) -> Option<Action> {
    Some(match key {
        KeyCode::Tab if mods.shift_key() => Action::CycleDisplay(-1),
        KeyCode::Tab => Action::CycleDisplay(1),
        KeyCode::KeyP => Action::ToggleShadows,
        KeyCode::Digit1 => return Action::from_digit(1),
        KeyCode::Digit2 => return Action::from_digit(2),
        KeyCode::Digit3 => return Action::from_digit(3),
        KeyCode::Digit4 => return Action::from_digit(4),
        KeyCode::Digit5 => return Action::from_digit(5),
        KeyCode::Digit6 => return Action::from_digit(6),
        KeyCode::Digit7 => return Action::from_digit(7),
        KeyCode::Digit8 => return Action::from_digit(8),
        KeyCode::Digit9 => return Action::from_digit(9),
        KeyCode::KeyR => Action::ToggleReuse,
        KeyCode::KeyC => Action::PrintCamera,
        KeyCode::KeyH => Action::ToggleOverlay,
        KeyCode::KeyO => Action::ToggleOverlayDetail,
        KeyCode::F1 => Action::Help,
        KeyCode::F12 => Action::Screenshot,
        KeyCode::KeyG => Action::GroundTruth,
        KeyCode::KeyM => Action::ErrorMap,
        KeyCode::Escape => Action::Quit,
        _ => return None,
    })
}

/// Input gathered from window events between two frames.
#[derive(Default)]
pub struct Input {
    /// What the fly camera steps with; the caller clears `look` once it is applied.
    pub fly: FlyInput,
    mods: ModifiersState,
    /// The left button is held.
    dragging: bool,
    cursor: Option<(f64, f64)>,
}

impl Input {
    pub fn set_modifiers(&mut self, mods: ModifiersState) {
        self.mods = mods;
        self.fly.fast = mods.shift_key();
        self.fly.slow = mods.control_key();
    }

    /// A key went down or up. Movement keys (W A S D, Q E) set held state; a fresh press (not
    /// an auto-repeat) of another key returns its action, if it has one.
    pub fn key(&mut self, key: KeyCode, pressed: bool, repeat: bool) -> Option<Action> {
        let v = if pressed { 1.0 } else { 0.0 };
        let f = &mut self.fly;
        match key {
            KeyCode::KeyW => f.forward = v,
            KeyCode::KeyS => f.back = v,
            KeyCode::KeyA => f.left = v,
            KeyCode::KeyD => f.right = v,
            KeyCode::KeyQ => f.down = v,
            KeyCode::KeyE => f.up = v,
            _ if pressed && !repeat => return action(key, self.mods),
            _ => {}
        }
        None
    }

    /// The left mouse button went down or up.
    pub fn left_button(&mut self, pressed: bool) {
        self.dragging = pressed;
    }

    /// The cursor moved to `p` (pixels): while dragging, the movement adds to the look.
    pub fn cursor_moved(&mut self, p: (f64, f64)) {
        if let (true, Some(last)) = (self.dragging, self.cursor) {
            self.fly.look.0 += p.0 - last.0;
            self.fly.look.1 += p.1 - last.1;
        }
        self.cursor = Some(p);
    }

    /// The window lost focus: key releases while unfocused never arrive, so stop moving (the
    /// modifiers are reported again on return and are kept meanwhile).
    pub fn focus_lost(&mut self) {
        let mods = self.mods;
        *self = Input::default();
        self.set_modifiers(mods);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_map_to_actions() {
        let none = ModifiersState::empty();
        assert_eq!(action(KeyCode::Tab, none), Some(Action::CycleDisplay(1)));
        assert_eq!(
            action(KeyCode::Tab, ModifiersState::SHIFT),
            Some(Action::CycleDisplay(-1))
        );
        assert_eq!(action(KeyCode::Escape, none), Some(Action::Quit));
        assert_eq!(action(KeyCode::KeyW, none), None, "movement is held");
    }

    #[test]
    fn movement_keys_are_held_and_other_presses_are_actions() {
        let mut input = Input::default();
        assert_eq!(input.key(KeyCode::KeyW, true, false), None);
        assert_eq!(input.key(KeyCode::KeyE, true, true), None);
        assert_eq!((input.fly.forward, input.fly.up), (1.0, 1.0));
        input.key(KeyCode::KeyW, false, false);
        assert_eq!(input.fly.forward, 0.0);
        assert_eq!(
            input.key(KeyCode::KeyR, true, false),
            Some(Action::ToggleReuse)
        );
        assert_eq!(input.key(KeyCode::KeyR, true, true), None, "auto-repeat");
        assert_eq!(input.key(KeyCode::KeyR, false, false), None, "release");
        input.set_modifiers(ModifiersState::SHIFT | ModifiersState::CONTROL);
        assert!(input.fly.fast && input.fly.slow);
        assert_eq!(
            input.key(KeyCode::Tab, true, false),
            Some(Action::CycleDisplay(-1))
        );
    }

    #[test]
    fn only_a_drag_looks_and_focus_loss_stops_moving() {
        let mut input = Input::default();
        input.cursor_moved((10.0, 10.0));
        input.cursor_moved((50.0, 30.0));
        assert_eq!(input.fly.look, (0.0, 0.0), "no button held");
        input.left_button(true);
        input.cursor_moved((60.0, 25.0));
        input.cursor_moved((70.0, 20.0));
        assert_eq!(input.fly.look, (20.0, -10.0));
        input.key(KeyCode::KeyA, true, false);
        input.set_modifiers(ModifiersState::SHIFT);
        input.focus_lost();
        assert!(input.fly.is_idle());
        assert!(input.fly.fast, "modifiers are kept");
        assert_eq!(
            action(KeyCode::Tab, input.mods),
            Some(Action::CycleDisplay(-1))
        );
    }
}
