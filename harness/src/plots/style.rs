//! How a series looks: a colour, a marker shape (filled or hollow) and a
//! line dash, from one fixed palette, so that within a chart every series
//! differs in colour *and* in marker or dash (it can be told apart in
//! grey too), and a method looks the same in every chart.

use plotters::style::RGBColor;

/// A marker shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Marker {
    /// No marker (guides).
    None,
    /// A disc or ring.
    Circle,
    /// A square.
    Square,
    /// A triangle pointing up.
    TriangleUp,
    /// A triangle pointing down.
    TriangleDown,
    /// A diamond.
    Diamond,
    /// A diagonal cross (×).
    Cross,
    /// An upright cross (+).
    Plus,
}

/// A line's dash pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Dash {
    /// A continuous line.
    Solid,
    /// Long dashes (rapier2d, references).
    Dashed,
    /// Short dots.
    Dotted,
    /// Long dashes with short gaps (a third guide beside dashed and dotted).
    Long,
    /// No line: markers only.
    None,
}

impl Dash {
    /// Dash and gap lengths (px) for plotters' dashed paths; `None` for a
    /// solid line or no line.
    pub fn pattern(self) -> Option<(u32, u32)> {
        match self {
            Dash::Dashed => Some((7, 4)),
            Dash::Dotted => Some((2, 3)),
            Dash::Long => Some((14, 4)),
            Dash::Solid | Dash::None => None,
        }
    }
}

/// The look of one series.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Style {
    /// Line and marker colour.
    pub colour: RGBColor,
    /// Marker shape.
    pub marker: Marker,
    /// A hollow marker (outline only), drawn over filled ones, so that a
    /// series under another stays visible.
    pub hollow: bool,
    /// The line.
    pub dash: Dash,
}

impl Style {
    /// The same style, dashed.
    pub const fn dashed(self) -> Self {
        Self {
            dash: Dash::Dashed,
            ..self
        }
    }

    /// The same style, dotted.
    pub const fn dotted(self) -> Self {
        Self {
            dash: Dash::Dotted,
            ..self
        }
    }

    /// What is left of the style in grey: the marker and the dash.
    pub fn grey_signature(&self) -> (Marker, bool, Dash) {
        (self.marker, self.hollow, self.dash)
    }
}

const fn style(r: u8, g: u8, b: u8, marker: Marker, hollow: bool) -> Style {
    Style {
        colour: RGBColor(r, g, b),
        marker,
        hollow,
        dash: Dash::Solid,
    }
}

/// Twelve styles, each with its own colour and its own marker: the tab10
/// colours without their grey (kept for references), then black, plum
/// and teal. Marker shapes run through filled, then hollow ones.
pub const PALETTE: [Style; 12] = [
    style(31, 119, 180, Marker::Circle, false),
    style(255, 127, 14, Marker::Square, false),
    style(44, 160, 44, Marker::TriangleUp, false),
    style(214, 39, 40, Marker::Diamond, false),
    style(148, 103, 189, Marker::TriangleDown, false),
    style(140, 86, 75, Marker::Circle, true),
    style(227, 119, 194, Marker::Cross, false),
    style(188, 189, 34, Marker::Plus, false),
    style(23, 190, 207, Marker::Square, true),
    style(25, 25, 25, Marker::TriangleUp, true),
    style(130, 20, 90, Marker::Diamond, true),
    style(0, 110, 90, Marker::TriangleDown, true),
];

/// The palette's `i`-th style (wrapping).
pub fn palette(i: usize) -> Style {
    PALETTE[i % PALETTE.len()]
}

/// The colour of closed forms and references: drawn as a wide pale line
/// under the curves that follow them, so both show where they agree.
pub const REFERENCE: Style = Style {
    colour: RGBColor(170, 170, 170),
    marker: Marker::None,
    hollow: false,
    dash: Dash::Solid,
};

/// A second reference in the same chart (the vacuum parabola beside the
/// drag reference): the same pale colour family, darker, dashed.
pub const REFERENCE_ALT: Style = Style {
    colour: RGBColor(120, 120, 120),
    marker: Marker::None,
    hollow: false,
    dash: Dash::Dashed,
};

/// Colour of slope guides and other annotations.
pub const GUIDE: RGBColor = RGBColor(90, 90, 90);

/// A fixed style per method id, so every chart agrees: the fixed-step
/// methods and Dormand–Prince solid, rapier2d-f64 dashed at each substep
/// count, references pale.
pub fn method_style(method: &str) -> Style {
    let index = match method {
        "explicit_euler" => 0,
        "semi_implicit_euler" => 1,
        "rk2_midpoint" => 2,
        "rk4" => 3,
        "velocity_verlet" => 4,
        "implicit_euler" => 5,
        "dormand_prince" => 6,
        "reference" | "exact" => return REFERENCE,
        "rapier2d_1sub" => 7,
        "rapier2d_4sub" => 8,
        "rapier2d_16sub" => 9,
        m if m.starts_with("rapier2d") => 10,
        _ => 11,
    };
    let s = PALETTE[index];
    if method.starts_with("rapier2d") {
        s.dashed()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_palette_differs_in_colour_and_in_grey() {
        for (i, a) in PALETTE.iter().enumerate() {
            for b in &PALETTE[i + 1..] {
                assert_ne!(a.colour, b.colour, "{a:?} {b:?}");
                assert_ne!(a.grey_signature(), b.grey_signature(), "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn every_rapier_substep_count_has_its_own_style() {
        let ids = [
            "explicit_euler",
            "semi_implicit_euler",
            "rk2_midpoint",
            "rk4",
            "velocity_verlet",
            "implicit_euler",
            "dormand_prince",
            "rapier2d_1sub",
            "rapier2d_4sub",
            "rapier2d_16sub",
        ];
        for (i, a) in ids.iter().enumerate() {
            for b in &ids[i + 1..] {
                let (sa, sb) = (method_style(a), method_style(b));
                assert_ne!(sa.colour, sb.colour, "{a} {b}");
                assert_ne!(sa.grey_signature(), sb.grey_signature(), "{a} {b}");
            }
        }
    }
}
