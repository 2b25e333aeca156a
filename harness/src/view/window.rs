//! The window: winit's event loop on the main thread, the simulation on
//! its own (`super::physics_thread`), and each frame drawn by the CPU
//! renderer into the canvas and handed to the window system by
//! softbuffer. Frames are paced at [`FRAME_RATE`] per second.
//!
//! The mouse: a left press on a dynamic body grabs it (a target joint
//! pulls it to the cursor until release); elsewhere a left or right drag
//! pans; the wheel zooms about the cursor. The keys are `super::input`'s.

use super::camera::Camera;
use super::canvas::Canvas;
use super::cpu_time::thread_cpu;
use super::frame::Frame;
use super::input::{self, Action, Overlay};
use super::overlays::Overlays;
use super::physics_thread::PhysicsThread;
use super::pick;
use super::renderer::{Hud, Renderer, panel_width};
use super::simulation::{Command, Drop, StateDump};
use super::state_out;
use anyhow::{Context as _, Result};
use nalgebra::Vector2;
use std::num::NonZeroU32;
use std::path::PathBuf;
use std::rc::Rc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, KeyEvent, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

/// Frames drawn per second.
pub const FRAME_RATE: f64 = 60.0;
/// A press within this many pixels of a particle grabs it.
const PICK_PX: f64 = 6.0;
/// A body dropped into a scene without dynamic bodies is this wide (px).
const DROP_PX: f64 = 40.0;
/// The wheel zooms by this factor per line.
const WHEEL_ZOOM: f64 = 1.15;
/// Frames left out of a `--frames` measurement at the start (the window
/// appearing, the first allocations).
const WARM_UP_FRAMES: u64 = 10;

/// What the window is asked to do.
#[derive(Debug, Clone)]
pub struct WindowOptions {
    /// The scene file, as given (for the title and the corner).
    pub scene: String,
    /// Window size (px).
    pub size: (u32, u32),
    /// Draw this many frames, print the frame rate, and close.
    pub frames: Option<u64>,
    /// Where D and closing write the state.
    pub state_out: Option<PathBuf>,
    /// Whether a reference engine runs beside (`--compare`): two panels,
    /// the engine's on the left.
    pub compare: bool,
    /// Overlays turned on at the start besides the defaults.
    pub show: Vec<super::input::Overlay>,
}

/// What the left button is doing.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Gesture {
    None,
    /// Pulling a body.
    Dragging,
    /// Moving the view; the last cursor position (px).
    Panning(f64, f64),
}

/// Sums of a `--frames` measurement.
#[derive(Debug, Default)]
struct Measure {
    frames: u64,
    started: Option<(Instant, StateDump)>,
    draw: Duration,
    /// CPU time of the drawing, where the platform says.
    draw_cpu: Option<Duration>,
    present: Duration,
    slowest: Duration,
}

/// The frame rate over the last second, for the corner.
#[derive(Debug)]
struct Rate {
    since: Instant,
    frames: u32,
    draw: Duration,
}

struct App {
    options: WindowOptions,
    physics: Option<PhysicsThread>,
    window: Option<Rc<Window>>,
    surface: Option<softbuffer::Surface<Rc<Window>, Rc<Window>>>,
    canvas: Canvas,
    renderer: Renderer,
    frame: Frame,
    camera: Option<Camera>,
    overlays: Overlays,
    hud: Hud,
    cursor: (f64, f64),
    gesture: Gesture,
    next_frame: Instant,
    rate: Rate,
    measure: Option<Measure>,
    error: Option<anyhow::Error>,
}

/// Opens the window and runs until it is closed (or `--frames` are drawn).
pub fn run(physics: PhysicsThread, options: WindowOptions) -> Result<()> {
    let event_loop = EventLoop::new().context(
        "no display to open the view's window on (set DISPLAY, or use --screenshot, which needs none)",
    )?;
    let mut app = App {
        hud: Hud {
            scene: options.scene.clone(),
            ..Hud::default()
        },
        measure: options.frames.map(|_| Measure::default()),
        options,
        physics: Some(physics),
        window: None,
        surface: None,
        canvas: Canvas::new(1, 1),
        renderer: Renderer::default(),
        frame: Frame::default(),
        camera: None,
        overlays: Overlays::default(),
        cursor: (0.0, 0.0),
        gesture: Gesture::None,
        next_frame: Instant::now(),
        rate: Rate {
            since: Instant::now(),
            frames: 0,
            draw: Duration::ZERO,
        },
        error: None,
    };
    for overlay in app.options.show.clone() {
        app.overlays.show(overlay);
    }
    app.send(Command::Needs(app.overlays.needs()));
    event_loop.run_app(&mut app)?;
    if let Some(physics) = app.physics.take() {
        physics.stop(Duration::from_secs(2));
    }
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

impl App {
    fn send(&self, command: Command) {
        if let Some(p) = &self.physics {
            p.send(command);
        }
    }

    /// The bodies' states now, asked of the simulation thread.
    fn dump(&self) -> Option<StateDump> {
        let (reply, answer) = std::sync::mpsc::channel();
        self.send(Command::Dump(reply));
        answer.recv_timeout(Duration::from_secs(5)).ok()
    }

    fn write_state(&mut self) {
        let Some(path) = self.options.state_out.clone() else {
            self.hud.note = "D writes the state where --state-out FILE says: none given".into();
            return;
        };
        match self.dump() {
            Some(dump) => match state_out::write(&path, &dump, self.camera.as_ref()) {
                Ok(()) => self.hud.note = format!("state written to {}", path.display()),
                Err(e) => self.hud.note = format!("{e:#}"),
            },
            None => self.hud.note = "the simulation did not answer within 5 s".into(),
        }
    }

    fn quit(&mut self, event_loop: &ActiveEventLoop) {
        if self.options.state_out.is_some() {
            self.write_state();
        }
        event_loop.exit();
    }

    /// The cursor in its panel's pixels, and whether that panel is the
    /// reference's (the right one of `--compare`).
    fn local_cursor(&self) -> (f64, f64, bool) {
        let half = f64::from(panel_width(self.canvas.width(), true));
        if self.options.compare && self.cursor.0 >= half {
            (self.cursor.0 - half, self.cursor.1, true)
        } else {
            (self.cursor.0, self.cursor.1, false)
        }
    }

    fn world_at_cursor(&self) -> Option<Vector2<f64>> {
        let (x, y, _) = self.local_cursor();
        self.camera.map(|c| c.to_world(x, y))
    }

    fn on_action(&mut self, action: Action, event_loop: &ActiveEventLoop) {
        match action {
            Action::TogglePause => self.send(Command::TogglePause),
            Action::Step => self.send(Command::Step),
            Action::Reset => self.send(Command::Reset),
            Action::Speed(f) => self.send(Command::Speed(f)),
            Action::Zoom(f) => {
                if let Some(c) = &mut self.camera {
                    c.zoom_at(0.5 * f64::from(c.width), 0.5 * f64::from(c.height), f);
                }
            }
            Action::Pan(dx, dy) => {
                if let Some(c) = &mut self.camera {
                    c.pan(dx, dy);
                }
            }
            Action::Fit => self.camera = None,
            Action::DropBox | Action::DropCircle => {
                if let (Some(at), Some(c)) = (self.world_at_cursor(), self.camera) {
                    let shape = if action == Action::DropBox {
                        Drop::Box
                    } else {
                        Drop::Circle
                    };
                    let size = DROP_PX / c.scale;
                    self.send(Command::Drop { shape, at, size });
                }
            }
            Action::SwitchModel => self.send(Command::SwitchModel),
            Action::Toggle(overlay) => {
                self.overlays.toggle(overlay);
                if overlay != Overlay::Help {
                    self.send(Command::Needs(self.overlays.needs()));
                }
            }
            Action::Dump => self.write_state(),
            Action::Quit => self.quit(event_loop),
        }
    }

    fn on_button(&mut self, button: MouseButton, state: ElementState) {
        match (button, state) {
            (MouseButton::Left, ElementState::Pressed) => {
                let Some(camera) = self.camera else {
                    return;
                };
                let (x, y, in_reference) = self.local_cursor();
                if in_reference {
                    // The reference's bodies are not dragged: a pan.
                    self.gesture = Gesture::Panning(self.cursor.0, self.cursor.1);
                    return;
                }
                let at = camera.to_world(x, y);
                let body = pick::body_at(
                    &self.frame.looks,
                    &self.frame.states,
                    &self.frame.removed,
                    at,
                    PICK_PX / camera.scale,
                );
                self.gesture = match body {
                    Some(body) => {
                        self.send(Command::Grab { body, at });
                        Gesture::Dragging
                    }
                    None => Gesture::Panning(self.cursor.0, self.cursor.1),
                };
            }
            (MouseButton::Right | MouseButton::Middle, ElementState::Pressed) => {
                self.gesture = Gesture::Panning(self.cursor.0, self.cursor.1);
            }
            (_, ElementState::Pressed) => {}
            (_, ElementState::Released) => {
                if self.gesture == Gesture::Dragging {
                    self.send(Command::Release);
                }
                self.gesture = Gesture::None;
            }
        }
    }

    fn on_cursor(&mut self, x: f64, y: f64) {
        self.cursor = (x, y);
        match self.gesture {
            Gesture::Dragging => {
                if let Some(at) = self.world_at_cursor() {
                    self.send(Command::DragTo(at));
                }
            }
            Gesture::Panning(x0, y0) => {
                if let Some(c) = &mut self.camera {
                    c.pan(x - x0, y - y0);
                }
                self.gesture = Gesture::Panning(x, y);
            }
            Gesture::None => {}
        }
    }

    fn resize(&mut self, size: PhysicalSize<u32>) {
        let (w, h) = (size.width.max(1), size.height.max(1));
        self.canvas.resize(w, h);
        let panel = panel_width(w, self.options.compare);
        if let Some(c) = &mut self.camera {
            c.resize(panel, h);
        }
        if let Some(surface) = &mut self.surface {
            let nz = |v: u32| NonZeroU32::new(v).unwrap_or(NonZeroU32::MIN);
            if let Err(e) = surface.resize(nz(w), nz(h)) {
                self.error = Some(anyhow::anyhow!("resizing the window's buffer: {e}"));
            }
        }
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(p) = &self.physics {
            p.take_frame(&mut self.frame);
        }
        if self.frame.looks.is_empty() {
            return;
        }
        let panel = panel_width(self.canvas.width(), self.options.compare);
        let camera = *self
            .camera
            .get_or_insert_with(|| Camera::fit_frame(&self.frame, panel, self.canvas.height()));
        let started = Instant::now();
        let cpu = thread_cpu();
        self.renderer.draw(
            &mut self.canvas,
            &self.frame,
            &camera,
            &self.overlays,
            &self.hud,
        );
        let drawn = Instant::now();
        let draw_cpu = cpu.zip(thread_cpu()).map(|(a, b)| b.saturating_sub(a));
        let Some(surface) = &mut self.surface else {
            return;
        };
        let presented = surface.buffer_mut().and_then(|mut buffer| {
            let n = buffer.len().min(self.canvas.pixels().len());
            buffer[..n].copy_from_slice(&self.canvas.pixels()[..n]);
            buffer.present()
        });
        if let Err(e) = presented {
            self.error = Some(anyhow::anyhow!("drawing into the window: {e}"));
            event_loop.exit();
            return;
        }
        let done = Instant::now();
        self.count([started, drawn, done], draw_cpu, event_loop);
    }

    /// Counts a frame drawn from `started` to `drawn` and presented at
    /// `done`.
    fn count(
        &mut self,
        [started, drawn, done]: [Instant; 3],
        draw_cpu: Option<Duration>,
        event_loop: &ActiveEventLoop,
    ) {
        self.rate.frames += 1;
        self.rate.draw += drawn - started;
        let since = done.saturating_duration_since(self.rate.since);
        if since >= Duration::from_secs(1) {
            self.hud.fps = Some(f64::from(self.rate.frames) / since.as_secs_f64());
            self.hud.draw_ms =
                Some(1e3 * self.rate.draw.as_secs_f64() / f64::from(self.rate.frames));
            self.rate = Rate {
                since: done,
                frames: 0,
                draw: Duration::ZERO,
            };
        }
        let Some(wanted) = self.options.frames else {
            return;
        };
        let Some(m) = &mut self.measure else {
            return;
        };
        m.frames += 1;
        if m.started.is_none() {
            if m.frames >= WARM_UP_FRAMES {
                let dump = self.dump();
                if let (Some(m), Some(dump)) = (&mut self.measure, dump) {
                    *m = Measure {
                        started: Some((Instant::now(), dump)),
                        draw_cpu: Some(Duration::ZERO),
                        ..Measure::default()
                    };
                }
            }
            return;
        }
        m.draw += drawn - started;
        m.draw_cpu = m.draw_cpu.zip(draw_cpu).map(|(sum, d)| sum + d);
        m.present += done - drawn;
        m.slowest = m.slowest.max(done - started);
        if m.frames >= wanted {
            let end = self.dump();
            if let (Some(m), Some(end)) = (self.measure.take(), end) {
                print_measure(&m, &end, &self.frame);
            }
            self.quit(event_loop);
        }
    }
}

/// Prints what `--frames` measured.
fn print_measure(m: &Measure, end: &StateDump, frame: &Frame) {
    let Some((began, start)) = &m.started else {
        return;
    };
    let wall = began.elapsed().as_secs_f64();
    let n = m.frames.max(1) as f64;
    let steps = end.steps.saturating_sub(start.steps);
    let sim = end.time - start.time;
    let stepping = end.stepping_seconds - start.stepping_seconds;
    println!(
        "view: {} frames in {wall:.2} s: {:.1} frames/s ({} bodies)",
        m.frames,
        n / wall,
        frame.status.bodies
    );
    let cpu = |seconds: Option<f64>, per: f64| {
        seconds.map_or(String::new(), |s| {
            format!(" ({:.2} ms of CPU)", 1e3 * s / per)
        })
    };
    println!(
        "  per frame (window thread): draw {:.2} ms{}, present {:.2} ms; slowest frame {:.2} ms",
        1e3 * m.draw.as_secs_f64() / n,
        cpu(m.draw_cpu.map(|d| d.as_secs_f64()), n),
        1e3 * m.present.as_secs_f64() / n,
        1e3 * m.slowest.as_secs_f64()
    );
    let per_step = steps.max(1) as f64;
    let step_cpu = end
        .stepping_cpu_seconds
        .zip(start.stepping_cpu_seconds)
        .map(|(b, a)| b - a);
    println!(
        "  physics (own thread): {steps} steps, {:.2} ms{} per step, {:.2} steps per frame, \
         {:.3} s simulated in {wall:.2} s (×{:.2} real time)",
        1e3 * stepping / per_step,
        cpu(step_cpu, per_step),
        steps as f64 / n,
        sim,
        sim / wall
    );
    if let (Some(b), Some(a)) = (&end.reference, &start.reference) {
        let steps = b.steps.saturating_sub(a.steps);
        let per_step = steps.max(1) as f64;
        let cpu_seconds = b
            .stepping_cpu_seconds
            .zip(a.stepping_cpu_seconds)
            .map(|(b, a)| b - a);
        println!(
            "  reference (same thread, one step after each of ours): {} ({}), {steps} steps, \
             {:.2} ms{} per step",
            b.engine,
            b.build,
            1e3 * (b.stepping_seconds - a.stepping_seconds) / per_step,
            cpu(cpu_seconds, per_step),
        );
    }
    println!(
        "  wall times include waiting for a core: on a machine shared with other work, \
         the CPU times say what the view costs"
    );
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        let (w, h) = self.options.size;
        let attributes = Window::default_attributes()
            .with_title(format!("harness view — {}", self.options.scene))
            .with_inner_size(PhysicalSize::new(w, h));
        let opened = event_loop
            .create_window(attributes)
            .map_err(anyhow::Error::from)
            .and_then(|window| {
                let window = Rc::new(window);
                let context = softbuffer::Context::new(Rc::clone(&window))
                    .map_err(|e| anyhow::anyhow!("{e}"))?;
                let surface = softbuffer::Surface::new(&context, Rc::clone(&window))
                    .map_err(|e| anyhow::anyhow!("{e}"))?;
                Ok((window, surface))
            });
        match opened {
            Ok((window, surface)) => {
                let size = window.inner_size();
                self.window = Some(window);
                self.surface = Some(surface);
                self.resize(size);
            }
            Err(e) => {
                self.error = Some(e.context("opening the view's window"));
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => self.quit(event_loop),
            WindowEvent::Resized(size) => self.resize(size),
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            WindowEvent::KeyboardInput {
                event:
                    KeyEvent {
                        logical_key,
                        state: ElementState::Pressed,
                        ..
                    },
                ..
            } => {
                if let Some(action) = input::action(&logical_key) {
                    self.on_action(action, event_loop);
                }
            }
            WindowEvent::CursorMoved { position, .. } => self.on_cursor(position.x, position.y),
            WindowEvent::MouseInput { state, button, .. } => self.on_button(button, state),
            WindowEvent::MouseWheel { delta, .. } => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                let (x, y, _) = self.local_cursor();
                if let Some(c) = &mut self.camera {
                    c.zoom_at(x, y, WHEEL_ZOOM.powf(lines));
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        if now >= self.next_frame {
            if let Some(w) = &self.window {
                w.request_redraw();
            }
            let period = Duration::from_secs_f64(1.0 / FRAME_RATE);
            self.next_frame += period;
            if self.next_frame < now {
                self.next_frame = now + period;
            }
        }
        event_loop.set_control_flow(ControlFlow::WaitUntil(self.next_frame));
    }
}
