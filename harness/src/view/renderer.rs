//! Drawing a [`Frame`] into the [`Canvas`]: a light grid in metres with a
//! scale bar, every body at its pose and true size (static ones first),
//! the overlays, and the text: the live numbers at the top, the keys at
//! the bottom. The same code draws the window and `--screenshot`. With
//! `--compare`, two panels side by side through the same camera: the
//! engine's on the left, the reference's on the right, each titled with
//! its engine and build.

use super::camera::Camera;
use super::canvas::{Canvas, Rgb, mix, rgb};
use super::frame::{Frame, NO_ISLAND};
use super::glyphs::Glyphs;
use super::input::HELP;
use super::overlays::{self, Overlays};
use engine::BodyKind;
use nalgebra::Rotation2;

const BACKGROUND: Rgb = rgb(250, 250, 247);
const GRID: Rgb = rgb(232, 232, 228);
const INK: Rgb = rgb(25, 25, 25);
const PANEL: Rgb = rgb(255, 255, 255);
const WARNING: Rgb = rgb(190, 20, 20);
const ASLEEP: Rgb = rgb(150, 150, 150);
/// Grid lines are at least this far apart (px).
const GRID_MIN_PX: f64 = 40.0;
/// Text size (px).
const TEXT_PX: f32 = 14.0;

/// What the window adds to the frame's own numbers.
#[derive(Debug, Clone, Default)]
pub struct Hud {
    /// The scene file, as given.
    pub scene: String,
    /// Frames per second drawn, over the last second.
    pub fps: Option<f64>,
    /// Time to draw a frame (ms), over the last second.
    pub draw_ms: Option<f64>,
    /// The window's last word (a state written, a key refused), if any.
    pub note: String,
}

/// The divider between the two panels of `--compare`.
const DIVIDER: Rgb = rgb(60, 60, 60);

/// Draws frames; keeps its glyphs and scratch buffers between them.
#[derive(Debug)]
pub struct Renderer {
    glyphs: Glyphs,
    points: Vec<(f64, f64)>,
    /// The two panels of `--compare`, drawn apart and copied side by side.
    panels: Option<(Canvas, Canvas)>,
}

impl Default for Renderer {
    fn default() -> Self {
        Self {
            glyphs: Glyphs::new(TEXT_PX),
            points: Vec::new(),
            panels: None,
        }
    }
}

/// The width (px) of one panel of a canvas `width` wide: the whole, or
/// the left half with `--compare` (the right one takes the rest).
pub fn panel_width(width: u32, compare: bool) -> u32 {
    if compare { (width / 2).max(1) } else { width }
}

impl Renderer {
    /// Draws `frame` as `camera` sees it with the overlays `on`; with a
    /// reference frame, the two panels side by side, `camera` being a
    /// panel's ([`panel_width`] wide).
    pub fn draw(
        &mut self,
        canvas: &mut Canvas,
        frame: &Frame,
        camera: &Camera,
        on: &Overlays,
        hud: &Hud,
    ) {
        let Some(reference) = &frame.reference else {
            self.draw_panel(canvas, frame, camera, on, hud);
            return;
        };
        let (w, h) = (canvas.width(), canvas.height());
        let half = panel_width(w, true);
        let (mut left, mut right) = self
            .panels
            .take()
            .unwrap_or_else(|| (Canvas::new(1, 1), Canvas::new(1, 1)));
        if (left.width(), left.height()) != (half, h) {
            left.resize(half, h);
        }
        if (right.width(), right.height()) != (w - half, h) {
            right.resize(w - half, h);
        }
        self.draw_panel(&mut left, frame, camera, on, hud);
        // The reference has its states only: no contacts, joints, sleep or
        // paths to show; its numbers without the window's.
        let reference_on = Overlays {
            contacts: false,
            joints: false,
            sleeping: false,
            paths: false,
            profile: false,
            help: false,
            ..*on
        };
        let reference_hud = Hud {
            scene: hud.scene.clone(),
            ..Hud::default()
        };
        let mut right_camera = *camera;
        right_camera.resize(w - half, h);
        self.draw_panel(
            &mut right,
            reference,
            &right_camera,
            &reference_on,
            &reference_hud,
        );
        canvas.blit(&left, 0);
        canvas.blit(&right, half);
        let x = f64::from(half) - 0.5;
        canvas.line(x, 0.0, x, f64::from(h), DIVIDER);
        self.panels = Some((left, right));
    }

    /// Draws one panel.
    fn draw_panel(
        &mut self,
        canvas: &mut Canvas,
        frame: &Frame,
        camera: &Camera,
        on: &Overlays,
        hud: &Hud,
    ) {
        canvas.clear(BACKGROUND);
        grid(canvas, camera);
        if on.paths {
            overlays::paths(canvas, frame, camera);
        }
        for pass in [true, false] {
            for id in 0..frame.looks.len().min(frame.states.len()) {
                let is_static = frame.looks[id].kind != BodyKind::Dynamic;
                if is_static == pass && !frame.removed.get(id).copied().unwrap_or(false) {
                    self.body(canvas, frame, camera, on, id);
                }
            }
        }
        if on.sleeping {
            overlays::islands(canvas, frame, camera);
        }
        overlays::over_bodies(canvas, frame, camera, on);
        let help_top = self.text(canvas, frame, on, hud);
        self.scale_bar(canvas, camera, help_top);
    }

    fn body(
        &mut self,
        canvas: &mut Canvas,
        frame: &Frame,
        camera: &Camera,
        on: &Overlays,
        id: usize,
    ) {
        let look = &frame.looks[id];
        let state = &frame.states[id];
        let (cx, cy) = camera.to_screen(state.position);
        let reach = look.radius * camera.scale + 3.0;
        let (w, h) = (f64::from(canvas.width()), f64::from(canvas.height()));
        if cx + reach < 0.0 || cy + reach < 0.0 || cx - reach > w || cy - reach > h {
            return;
        }
        let asleep = on.sleeping && frame.asleep.get(id).copied().unwrap_or(false);
        let island = frame
            .island_of
            .get(id)
            .copied()
            .filter(|&i| on.sleeping && i != NO_ISLAND);
        // An island's bodies are tinted and outlined in its colour.
        let own = match island {
            Some(i) => mix(look.colour, overlays::island_colour(i as usize), 0.45),
            None => look.colour,
        };
        let fill = if asleep { mix(own, ASLEEP, 0.7) } else { own };
        let outline = match island {
            Some(i) if !asleep => mix(overlays::island_colour(i as usize), rgb(0, 0, 0), 0.3),
            _ => mix(fill, rgb(0, 0, 0), 0.45),
        };
        let detailed = look.radius * camera.scale >= 4.0;
        if look.is_particle() {
            canvas.fill_circle(cx, cy, 4.0, fill);
            canvas.circle(cx, cy, 4.0, outline);
            return;
        }
        let rotation = Rotation2::new(state.angle);
        for polygon in &look.polygons {
            self.points.clear();
            self.points.extend(
                polygon
                    .iter()
                    .map(|v| camera.to_screen(state.position + rotation * v)),
            );
            canvas.fill_convex(&self.points, fill);
            if detailed {
                for (i, a) in self.points.iter().enumerate() {
                    let b = self.points[(i + 1) % self.points.len()];
                    canvas.line(a.0, a.1, b.0, b.1, outline);
                }
            }
        }
        for (centre, r) in &look.circles {
            let c = state.position + rotation * centre;
            let (x, y) = camera.to_screen(c);
            let r_px = r * camera.scale;
            canvas.fill_circle(x, y, r_px, fill);
            if detailed {
                canvas.circle(x, y, r_px, outline);
                // A radius shows the turn.
                let edge = camera.to_screen(c + rotation * nalgebra::Vector2::new(*r, 0.0));
                canvas.line(x, y, edge.0, edge.1, outline);
            }
        }
    }

    /// A bar of a round length in metres, bottom right, above the help
    /// text (whose top is `help_top` px, if shown).
    fn scale_bar(&mut self, canvas: &mut Canvas, camera: &Camera, help_top: Option<f32>) {
        let metres = nice_step(100.0 / camera.scale);
        let px = metres * camera.scale;
        let (w, h) = (f64::from(canvas.width()), f64::from(canvas.height()));
        let y = help_top.map_or(h - 60.0, |top| (h - 60.0).min(f64::from(top) - 12.0));
        let x1 = w - 16.0;
        let x0 = x1 - px;
        canvas.line(x0, y, x1, y, INK);
        canvas.line(x0, y - 4.0, x0, y + 4.0, INK);
        canvas.line(x1, y - 4.0, x1, y + 4.0, INK);
        let label = format!("{} m", short(metres));
        let width = f64::from(self.glyphs.width(&label));
        self.glyphs.draw(
            canvas,
            &label,
            (x0 + 0.5 * (px - width)) as f32,
            (y - 22.0) as f32,
            INK,
        );
    }

    /// The numbers at the top and the help at the bottom; returns the
    /// help's top (px), if shown.
    fn text(
        &mut self,
        canvas: &mut Canvas,
        frame: &Frame,
        on: &Overlays,
        hud: &Hud,
    ) -> Option<f32> {
        let s = &frame.status;
        let mut lines: Vec<(String, Rgb)> = Vec::new();
        if !s.label.is_empty() {
            lines.push((s.label.clone(), INK));
        }
        let state = if s.running {
            format!("running ×{}", short(s.speed))
        } else {
            "paused".to_owned()
        };
        let achieved = match s.achieved_speed {
            Some(a) if s.running => format!(" · achieved ×{a:.2}"),
            _ => String::new(),
        };
        lines.push((
            format!(
                "{} · t = {:.3} s · step {} (dt = {} s) · {state}{achieved}",
                hud.scene,
                s.time,
                s.steps,
                short(s.dt),
            ),
            INK,
        ));
        let mut counts = format!(
            "model {} · {} bodies ({} asleep) · {} joints",
            s.model, s.bodies, s.asleep, s.joints
        );
        if let Some(ms) = s.step_ms {
            counts.push_str(&format!(" · step {ms:.2} ms"));
        }
        if let (Some(fps), Some(draw)) = (hud.fps, hud.draw_ms) {
            counts.push_str(&format!(" · draw {draw:.2} ms · {fps:.0} frames/s"));
        }
        lines.push((counts, INK));
        if on.profile {
            let phases: Vec<String> = s
                .phases
                .iter()
                .filter(|(_, ms)| *ms >= 0.005)
                .map(|(name, ms)| format!("{name} {ms:.2}"))
                .collect();
            if !phases.is_empty() {
                lines.push((format!("profile, ms per step: {}", phases.join(" · ")), INK));
            }
            let counters: Vec<String> = s
                .counters
                .iter()
                .filter(|(_, n)| *n > 0.0)
                .map(|(name, n)| format!("{name} {n:.0}"))
                .collect();
            if !counters.is_empty() {
                lines.push((format!("per step: {}", counters.join(" · ")), INK));
            }
        }
        if on.contacts {
            if let Some(scale) = s.impulse_scale {
                lines.push((
                    format!(
                        "contact normals: length = normal impulse over the last step, {} px per \
                         N·s (largest {:.3} N·s)",
                        short(scale.px_per_newton_second),
                        scale.largest
                    ),
                    INK,
                ));
            } else if !frame.contacts.is_empty() {
                lines.push((
                    "contact normals: unit length (this model reports no impulses)".into(),
                    INK,
                ));
            }
        }
        if on.sleeping && !frame.islands.is_empty() {
            let asleep = frame.islands.iter().filter(|i| i.asleep).count();
            lines.push((
                format!(
                    "{} islands ({asleep} asleep): each its own colour, boxed when of 2 or more \
                     bodies, greyed asleep",
                    frame.islands.len()
                ),
                INK,
            ));
        }
        for message in [&s.message, &hud.note] {
            if !message.is_empty() {
                lines.push((message.clone(), WARNING));
            }
        }
        let line_h = self.glyphs.line_height();
        self.panel(canvas, &lines, Some(6.0), line_h);
        if on.help {
            let mut legend = on.legend();
            if let (true, Some(why)) = (on.sleeping, &frame.islands_missing) {
                legend.push_str(&format!(" (islands: none, {why})"));
            }
            let help = [(HELP.to_owned(), INK), (legend, INK)];
            return Some(self.panel(canvas, &help, None, line_h));
        }
        None
    }

    /// Lines of text on a pale band from `top` (px; `None`: ending at the
    /// bottom), each wrapped at spaces to the canvas's width; returns the
    /// band's top (px).
    fn panel(
        &mut self,
        canvas: &mut Canvas,
        lines: &[(String, Rgb)],
        top: Option<f32>,
        line_h: f32,
    ) -> f32 {
        let room = (canvas.width() as f32 - 24.0).max(40.0);
        let mut wrapped: Vec<(String, Rgb)> = Vec::new();
        for (line, colour) in lines {
            let mut current = String::new();
            for word in line.split(' ') {
                let candidate = if current.is_empty() {
                    word.to_owned()
                } else {
                    format!("{current} {word}")
                };
                if !current.is_empty() && self.glyphs.width(&candidate) > room {
                    wrapped.push((std::mem::take(&mut current), *colour));
                    current = word.to_owned();
                } else {
                    current = candidate;
                }
            }
            wrapped.push((current, *colour));
        }
        let lines = &wrapped;
        let top = top.unwrap_or(canvas.height() as f32 - lines.len() as f32 * line_h - 8.0);
        let width = lines
            .iter()
            .map(|(l, _)| self.glyphs.width(l))
            .fold(0.0, f32::max);
        canvas.shade_rect(
            2,
            top as i64 - 2,
            width as i64 + 12,
            (line_h * lines.len() as f32) as i64 + 4,
            PANEL,
            0.8,
        );
        for (i, (line, colour)) in lines.iter().enumerate() {
            self.glyphs
                .draw(canvas, line, 8.0, top + i as f32 * line_h, *colour);
        }
        top
    }
}

/// Grid lines every round number of metres, at least [`GRID_MIN_PX`] apart.
fn grid(canvas: &mut Canvas, camera: &Camera) {
    let step = nice_step(GRID_MIN_PX / camera.scale);
    let (w, h) = (f64::from(canvas.width()), f64::from(canvas.height()));
    let lo = camera.to_world(0.0, h);
    let hi = camera.to_world(w, 0.0);
    let mut x = (lo.x / step).floor() * step;
    while x <= hi.x {
        let (px, _) = camera.to_screen(nalgebra::Vector2::new(x, 0.0));
        canvas.line(px, 0.0, px, h, GRID);
        x += step;
    }
    let mut y = (lo.y / step).floor() * step;
    while y <= hi.y {
        let (_, py) = camera.to_screen(nalgebra::Vector2::new(0.0, y));
        canvas.line(0.0, py, w, py, GRID);
        y += step;
    }
}

/// The smallest of 1, 2, 5 × 10ⁿ at least `at_least`.
fn nice_step(at_least: f64) -> f64 {
    let base = 10f64.powf(at_least.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * base)
        .find(|&v| v >= at_least)
        .unwrap_or(10.0 * base)
}

/// A number in few characters: `0.01667`, `2`, `0.5`.
fn short(v: f64) -> String {
    let text = format!("{v:.4}");
    let text = if v.abs() >= 1e-3 {
        text
    } else {
        format!("{v:.2e}")
    };
    if text.contains('.') && !text.contains('e') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn grid_steps_are_round_and_large_enough() {
        assert_eq!(super::nice_step(0.3), 0.5);
        assert_eq!(super::nice_step(3.0), 5.0);
        assert_eq!(super::nice_step(11.0), 20.0);
        assert_eq!(super::short(1.0 / 60.0), "0.0167");
        assert_eq!(super::short(2.0), "2");
    }
}
