//! The font of every picture and chart: DejaVu Sans, shipped in
//! `harness/assets/` and compiled into the binary, so that text renders
//! (and is measured) identically on any machine, with no system fonts
//! (plotters' `ab_glyph` feature).
//!
//! Call [`ensure_fonts`] before drawing any text with plotters; it is cheap
//! after the first call. Use the family [`FAMILY`].

use ab_glyph::FontRef;
use plotters::style::FontStyle;
use std::sync::OnceLock;

/// The family name the font is registered under, for `("sans-serif", 14)`
/// style tuples.
pub const FAMILY: &str = "sans-serif";

static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Registers DejaVu Sans as [`FAMILY`] for the normal, bold, italic and
/// oblique styles (one face for all). Idempotent; returns whether the font
/// is available. A failure (a corrupt font file, which would be a build
/// mistake) is logged, and text then fails to draw with an error rather
/// than a panic.
pub fn ensure_fonts() -> bool {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    *REGISTERED.get_or_init(|| {
        let styles = [
            FontStyle::Normal,
            FontStyle::Bold,
            FontStyle::Italic,
            FontStyle::Oblique,
        ];
        let ok = styles
            .into_iter()
            .all(|style| plotters::style::register_font(FAMILY, style, FONT).is_ok());
        if !ok {
            tracing::error!("the embedded font DejaVuSans.ttf could not be registered");
        }
        ok
    })
}

/// The font itself, for drawing text on bitmaps without plotters (see
/// `pictures::text`). `None` only if the embedded file is corrupt.
pub(crate) fn face() -> Option<&'static FontRef<'static>> {
    static FACE: OnceLock<Option<FontRef<'static>>> = OnceLock::new();
    FACE.get_or_init(|| FontRef::try_from_slice(FONT).ok())
        .as_ref()
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_embedded_font_registers() {
        assert!(super::ensure_fonts());
        assert!(super::ensure_fonts());
    }
}
