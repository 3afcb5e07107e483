//! winit's event loop: window events to viewer input and actions, redraws to frames, and the
//! loop's pace (polling while frames are drawn, slow polling while minimised).

use super::App;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, KeyEvent, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::keyboard::PhysicalKey;
use winit::window::WindowId;

/// Mouse buttons and wheel, which the overlay may take; keys always reach the viewer (the
/// overlay has no text fields), and so do cursor moves (a drag begun outside the panel keeps
/// turning the camera across it).
fn is_pointer(event: &WindowEvent) -> bool {
    matches!(
        event,
        WindowEvent::MouseInput { .. } | WindowEvent::MouseWheel { .. }
    )
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.live.is_some() || self.error.is_some() {
            return;
        }
        event_loop.set_control_flow(ControlFlow::Poll);
        if let Err(e) = self.start(event_loop) {
            self.fail(event_loop, e);
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        if let Some(live) = self.live.as_mut() {
            let window = live.window.clone();
            if let Some(o) = live.overlay.as_mut() {
                if o.on_window_event(&window, &event) && is_pointer(&event) {
                    return; // a drag or click on the panel does not turn the camera
                }
            }
        }
        let input = &mut self.viewer.input;
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(_) => {
                if let Some(live) = self.live.as_mut() {
                    live.swapchain.invalidate();
                }
            }
            WindowEvent::ModifiersChanged(m) => input.set_modifiers(m.state()),
            WindowEvent::KeyboardInput {
                event:
                    KeyEvent {
                        physical_key: PhysicalKey::Code(key),
                        state,
                        repeat,
                        ..
                    },
                ..
            } => {
                if let Some(a) = input.key(key, state == ElementState::Pressed, repeat) {
                    self.act(event_loop, a);
                }
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => input.left_button(state == ElementState::Pressed),
            WindowEvent::CursorMoved { position, .. } => {
                input.cursor_moved((position.x, position.y));
            }
            WindowEvent::Focused(false) => input.focus_lost(),
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.frame(event_loop) {
                    self.fail(event_loop, e);
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if self.error.is_some() || event_loop.exiting() {
            return;
        }
        if self.pause.zero_ticks > 0 {
            self.pause.zero_ticks -= 1;
            if self.pause.zero_ticks == 0 {
                // Back from the (scripted) zero extent: the swapchain is recreated.
                if let Some(live) = self.live.as_mut() {
                    live.swapchain.invalidate();
                }
            }
            event_loop.set_control_flow(ControlFlow::WaitUntil(
                Instant::now() + Duration::from_millis(5),
            ));
            if self.pause.zero_ticks > 0 {
                return;
            }
        }
        if self.pause.minimised {
            // Keep polling the surface at a low rate; a resize event also wakes the loop.
            event_loop.set_control_flow(ControlFlow::WaitUntil(
                Instant::now() + Duration::from_millis(50),
            ));
        } else {
            event_loop.set_control_flow(ControlFlow::Poll);
        }
        if let Some(live) = &self.live {
            live.window.request_redraw();
        }
    }

    fn exiting(&mut self, _event_loop: &ActiveEventLoop) {
        self.shutdown();
    }
}
