//! The keys: what each does, and the help line that lists them. (The
//! mouse: left-drag a body to pull it, left-drag elsewhere or right-drag
//! to pan, the wheel to zoom about the cursor: `super::window`.)

use winit::keyboard::{Key, NamedKey};

/// The help line drawn at the bottom of the window.
pub const HELP: &str = "Space run/pause · S step · R reset · +/− speed · wheel zoom · drag a body (or pan) · \
                        F fit · B box · C circle · M contact model · D dump · H help · Q quit";

/// An overlay a key toggles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Overlay {
    /// Contact points and normals.
    Contacts,
    /// Bounding boxes.
    Boxes,
    /// Joints.
    Joints,
    /// Sleeping bodies.
    Sleeping,
    /// Centres of mass.
    Centres,
    /// Paths.
    Paths,
    /// The step profile.
    Profile,
    /// The help line.
    Help,
}

/// What a key asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Action {
    /// Run or pause.
    TogglePause,
    /// One step.
    Step,
    /// Back to t = 0.
    Reset,
    /// Multiply the speed.
    Speed(f64),
    /// Zoom about the window's centre by this factor.
    Zoom(f64),
    /// Pan by this many pixels.
    Pan(f64, f64),
    /// Fit the scene in the window.
    Fit,
    /// Drop a box at the cursor.
    DropBox,
    /// Drop a circle at the cursor.
    DropCircle,
    /// The next contact model.
    SwitchModel,
    /// Toggle an overlay.
    Toggle(Overlay),
    /// Write the state (`--state-out`).
    Dump,
    /// Close the view.
    Quit,
}

/// Pixels an arrow key pans.
const PAN_PX: f64 = 60.0;

/// The action of a key, if any.
pub fn action(key: &Key) -> Option<Action> {
    Some(match key {
        Key::Named(NamedKey::Space) => Action::TogglePause,
        Key::Named(NamedKey::ArrowRight) => Action::Pan(-PAN_PX, 0.0),
        Key::Named(NamedKey::ArrowLeft) => Action::Pan(PAN_PX, 0.0),
        Key::Named(NamedKey::ArrowUp) => Action::Pan(0.0, PAN_PX),
        Key::Named(NamedKey::ArrowDown) => Action::Pan(0.0, -PAN_PX),
        Key::Named(NamedKey::PageUp) => Action::Zoom(1.25),
        Key::Named(NamedKey::PageDown) => Action::Zoom(0.8),
        Key::Named(NamedKey::Escape) => Action::Quit,
        Key::Character(c) => match c.to_lowercase().as_str() {
            "s" | "." => Action::Step,
            "r" => Action::Reset,
            "+" | "=" => Action::Speed(2.0),
            "-" => Action::Speed(0.5),
            "f" => Action::Fit,
            "b" => Action::DropBox,
            "c" => Action::DropCircle,
            "m" => Action::SwitchModel,
            "d" => Action::Dump,
            "q" => Action::Quit,
            "h" => Action::Toggle(Overlay::Help),
            "p" => Action::Toggle(Overlay::Profile),
            "1" => Action::Toggle(Overlay::Contacts),
            "2" => Action::Toggle(Overlay::Boxes),
            "3" => Action::Toggle(Overlay::Joints),
            "4" => Action::Toggle(Overlay::Sleeping),
            "5" => Action::Toggle(Overlay::Centres),
            "6" => Action::Toggle(Overlay::Paths),
            _ => return None,
        },
        _ => return None,
    })
}

impl super::overlays::Overlays {
    /// Flips `overlay`.
    pub fn toggle(&mut self, overlay: Overlay) {
        let flag = match overlay {
            Overlay::Contacts => &mut self.contacts,
            Overlay::Boxes => &mut self.boxes,
            Overlay::Joints => &mut self.joints,
            Overlay::Sleeping => &mut self.sleeping,
            Overlay::Centres => &mut self.centres,
            Overlay::Paths => &mut self.paths,
            Overlay::Profile => &mut self.profile,
            Overlay::Help => &mut self.help,
        };
        *flag = !*flag;
    }

    /// Turns `overlay` on (left on if it was).
    pub fn show(&mut self, overlay: Overlay) {
        let before = *self;
        self.toggle(overlay);
        if before
            .flags()
            .iter()
            .zip(self.flags())
            .any(|(&b, a)| b && !a)
        {
            *self = before;
        }
    }

    fn flags(&self) -> [bool; 8] {
        [
            self.contacts,
            self.boxes,
            self.joints,
            self.sleeping,
            self.centres,
            self.paths,
            self.profile,
            self.help,
        ]
    }
}
