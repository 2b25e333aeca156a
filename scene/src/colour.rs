//! Body colours for pictures (the harness draws; the engine ignores them).

use std::fmt;

/// An sRGB colour, written `"#rrggbb"` in a scene file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Colour {
    /// Red, 0–255.
    pub r: u8,
    /// Green, 0–255.
    pub g: u8,
    /// Blue, 0–255.
    pub b: u8,
}

impl Colour {
    /// The default cycle of bodies that move, matplotlib's "tab10" without
    /// its grey (kept for static bodies): the `i`-th body that is not static
    /// and has no `colour` gets `PALETTE[i % 9]`.
    pub const PALETTE: [Colour; 9] = [
        Colour::rgb(0x1f, 0x77, 0xb4),
        Colour::rgb(0xff, 0x7f, 0x0e),
        Colour::rgb(0x2c, 0xa0, 0x2c),
        Colour::rgb(0xd6, 0x27, 0x28),
        Colour::rgb(0x94, 0x67, 0xbd),
        Colour::rgb(0x8c, 0x56, 0x4b),
        Colour::rgb(0xe3, 0x77, 0xc2),
        Colour::rgb(0xbc, 0xbd, 0x22),
        Colour::rgb(0x17, 0xbe, 0xcf),
    ];

    /// A colour from its components.
    pub const fn rgb(r: u8, g: u8, b: u8) -> Self {
        Self { r, g, b }
    }

    /// Parses `"#rrggbb"` (hex digits in either case). `None` otherwise.
    pub fn parse_hex(text: &str) -> Option<Self> {
        let hex = text.strip_prefix('#')?;
        if hex.len() != 6 || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
            return None;
        }
        let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
        Some(Self::rgb(byte(0)?, byte(2)?, byte(4)?))
    }

    /// The default colour of a static body: grey, so that what does not
    /// move reads as the setting.
    pub const STATIC: Colour = Colour::rgb(0x7f, 0x7f, 0x7f);

    /// The palette colour of the `index`-th body that is not static.
    pub fn default_for(index: usize) -> Self {
        Self::PALETTE[index % Self::PALETTE.len()]
    }
}

/// `#rrggbb`, lower case.
impl fmt::Display for Colour {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_round_trips() {
        let c = Colour::parse_hex("#1F77b4").unwrap();
        assert_eq!(c, Colour::PALETTE[0]);
        assert_eq!(c.to_string(), "#1f77b4");
    }

    #[test]
    fn malformed_hex_is_refused() {
        for bad in ["1f77b4", "#1f77b", "#1f77b4ff", "#gg0000", "#é1234"] {
            assert_eq!(Colour::parse_hex(bad), None, "{bad}");
        }
    }
}
