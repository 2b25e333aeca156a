//! The overlays a user toggles over the bodies: contact points with their
//! normals, bounding boxes, joints, sleeping bodies, centres of mass,
//! recent paths, and the step profile. Each is drawn from the frame; the
//! ones that need the simulation to copy more out say so ([`Overlays::needs`]).

use super::camera::Camera;
use super::canvas::{Canvas, Rgb, rgb};
use super::frame::Frame;
use super::simulation::Needs;

/// Which overlays are on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Overlays {
    /// Contact points and normals.
    pub contacts: bool,
    /// Axis-aligned bounding boxes.
    pub boxes: bool,
    /// Joints: anchors and the lines to the bodies' centres.
    pub joints: bool,
    /// Islands coloured (the soft step's, where it keeps them) and
    /// sleeping bodies greyed.
    pub sleeping: bool,
    /// Centres of mass.
    pub centres: bool,
    /// Recent paths.
    pub paths: bool,
    /// The step profile and counters.
    pub profile: bool,
    /// The keys.
    pub help: bool,
}

impl Default for Overlays {
    fn default() -> Self {
        Self {
            contacts: false,
            boxes: false,
            joints: true,
            sleeping: true,
            centres: false,
            paths: false,
            profile: true,
            help: true,
        }
    }
}

impl Overlays {
    /// What the simulation must copy out for these overlays.
    pub fn needs(&self) -> Needs {
        Needs {
            contacts: self.contacts,
            joints: self.joints,
            paths: self.paths,
            islands: self.sleeping,
            profile: self.profile,
        }
    }

    /// The overlays' keys, names and states, for the help line.
    pub fn legend(&self) -> String {
        [
            ("1", "contacts", self.contacts),
            ("2", "boxes", self.boxes),
            ("3", "joints", self.joints),
            ("4", "sleeping", self.sleeping),
            ("5", "centres", self.centres),
            ("6", "paths", self.paths),
            ("P", "profile", self.profile),
        ]
        .iter()
        .map(|(key, name, on)| format!("{key} {name} {}", if *on { "on" } else { "off" }))
        .collect::<Vec<_>>()
        .join(" · ")
    }
}

/// Contact points.
const CONTACT: Rgb = rgb(220, 30, 30);
/// Contact normals.
const NORMAL: Rgb = rgb(0, 150, 40);
/// Bounding boxes.
const AABB: Rgb = rgb(200, 60, 200);
/// Joints.
const JOINT: Rgb = rgb(40, 140, 200);
/// Centres of mass.
const CENTRE: Rgb = rgb(20, 20, 20);
/// The drag's line and target.
const DRAG: Rgb = rgb(0, 170, 0);
/// Half the width of a contact point's mark (m), 1 to 2.5 px.
const CONTACT_MARK_M: f64 = 0.025;
/// A normal's length on screen (px) where the model gives no impulse.
const NORMAL_PX: f64 = 12.0;

/// Recent paths, under the bodies.
pub fn paths(canvas: &mut Canvas, frame: &Frame, camera: &Camera) {
    for (id, path) in &frame.paths {
        let Some(look) = frame.looks.get(*id) else {
            continue;
        };
        let colour = super::canvas::mix(look.colour, rgb(255, 255, 255), 0.4);
        for pair in path.windows(2) {
            let (a, b) = (camera.to_screen(pair[0]), camera.to_screen(pair[1]));
            canvas.line(a.0, a.1, b.0, b.1, colour);
        }
    }
}

/// The overlays drawn over the bodies.
pub fn over_bodies(canvas: &mut Canvas, frame: &Frame, camera: &Camera, on: &Overlays) {
    if on.boxes {
        boxes(canvas, frame, camera);
    }
    if on.joints {
        for j in &frame.joints {
            let a = camera.to_screen(j.anchor_a);
            let b = camera.to_screen(j.anchor_b);
            for (centre, anchor) in [(j.centre_a, a), (j.centre_b, b)] {
                if let Some(c) = centre {
                    let c = camera.to_screen(c);
                    canvas.line(c.0, c.1, anchor.0, anchor.1, JOINT);
                }
            }
            canvas.line(a.0, a.1, b.0, b.1, JOINT);
            canvas.fill_circle(a.0, a.1, 3.0, JOINT);
            canvas.fill_circle(b.0, b.1, 3.0, JOINT);
        }
    }
    if on.contacts {
        for c in &frame.contacts {
            let p = camera.to_screen(c.point);
            // Under the soft step, the normal's length is its impulse
            // (the frame's scale); otherwise a fixed length.
            let length_px = match (c.normal_impulse, frame.status.impulse_scale) {
                (Some(j), Some(scale)) => j.max(0.0) * scale.px_per_newton_second,
                _ => NORMAL_PX,
            };
            let tip = camera.to_screen(c.point + c.normal * (length_px / camera.scale));
            // A point's mark: 5 cm across, 2 to 5 px.
            let r = (CONTACT_MARK_M * camera.scale).clamp(1.0, 2.5);
            canvas.fill_convex(
                &[
                    (p.0 - r, p.1 - r),
                    (p.0 + r, p.1 - r),
                    (p.0 + r, p.1 + r),
                    (p.0 - r, p.1 + r),
                ],
                CONTACT,
            );
            // 3 px wide, to be seen over the bodies.
            let (dx, dy) = (tip.0 - p.0, tip.1 - p.1);
            let norm = dx.hypot(dy).max(1e-9);
            let (ox, oy) = (-dy / norm, dx / norm);
            for k in [-1.0, 0.0, 1.0] {
                let (x, y) = (ox * k, oy * k);
                canvas.line(p.0 + x, p.1 + y, tip.0 + x, tip.1 + y, NORMAL);
            }
        }
    }
    if on.centres {
        for (id, s) in frame.states.iter().enumerate() {
            if frame.removed.get(id).copied().unwrap_or(false) {
                continue;
            }
            let (x, y) = camera.to_screen(s.position);
            canvas.line(x - 4.0, y, x + 4.0, y, CENTRE);
            canvas.line(x, y - 4.0, x, y + 4.0, CENTRE);
        }
    }
    if let Some((grabbed, target)) = frame.drag {
        let (a, b) = (camera.to_screen(grabbed), camera.to_screen(target));
        canvas.line(a.0, a.1, b.0, b.1, DRAG);
        canvas.circle(b.0, b.1, 4.0, DRAG);
        canvas.fill_circle(a.0, a.1, 2.5, DRAG);
    }
}

/// A distinct colour for island `id` (hues a golden angle apart).
pub fn island_colour(id: usize) -> Rgb {
    let hue = (id as f64 * 0.618_033_988_749_895).fract() * 6.0;
    let x = 1.0 - (hue % 2.0 - 1.0).abs();
    let (r, g, b) = match hue as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    // Saturation 0.75, value 0.85.
    let channel = |c: f64| (255.0 * 0.85 * (1.0 - 0.75 * (1.0 - c))).round() as u8;
    rgb(channel(r), channel(g), channel(b))
}

/// The soft step's islands of two or more bodies: the box around each in
/// its colour, greyed while it sleeps.
pub fn islands(canvas: &mut Canvas, frame: &Frame, camera: &Camera) {
    for island in frame.islands.iter().filter(|i| i.bodies >= 2) {
        let colour = if island.asleep {
            super::canvas::mix(island_colour(island.id), rgb(160, 160, 160), 0.7)
        } else {
            island_colour(island.id)
        };
        let (a, b) = (camera.to_screen(island.lo), camera.to_screen(island.hi));
        canvas.rect(a.0 - 2.0, a.1 + 2.0, b.0 + 2.0, b.1 - 2.0, colour);
    }
}

/// Every shaped body's axis-aligned bounding box.
fn boxes(canvas: &mut Canvas, frame: &Frame, camera: &Camera) {
    for (id, look) in frame.looks.iter().enumerate() {
        if look.is_particle() || frame.removed.get(id).copied().unwrap_or(false) {
            continue;
        }
        let Some(s) = frame.states.get(id) else {
            continue;
        };
        let (lo, hi) = look.aabb(s);
        let (a, b) = (camera.to_screen(lo), camera.to_screen(hi));
        canvas.rect(a.0, a.1, b.0, b.1, AABB);
    }
}
