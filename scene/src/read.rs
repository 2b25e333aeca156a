//! Reading a scene file's bytes and decoding them, before any parsing.
//!
//! - Only a **regular file** is read: a FIFO would block until someone
//!   writes to it, a device such as `/dev/zero` never ends, a folder has
//!   no text. The kind is checked on the file's metadata, before opening it
//!   (opening a FIFO for reading already blocks).
//! - At most [`MAX_SCENE_BYTES`] are read: a scene is a page of text, and a
//!   file that grows while it is read is cut at the limit and refused.
//! - The text must be **UTF-8** (TOML's encoding). A byte-order mark of
//!   UTF-16 or UTF-32, or the zero bytes of UTF-16 without one, are named
//!   as such; an invalid byte is located (line, column and byte offset) with
//!   what it most likely is (a Latin-1 / Windows-1252 accent).

use crate::error::{ErrorKind, SceneError};
use crate::location::line_column;
use std::io::Read;
use std::path::Path;

/// The largest scene file read, 16 MiB: a thousand times the largest
/// scene of the project, still read and parsed in well under a second.
pub const MAX_SCENE_BYTES: u64 = 16 * 1024 * 1024;

/// Reads the scene file at `path` (named `origin` in errors) as text.
pub(crate) fn read_scene_file(path: &Path, origin: &str) -> Result<String, SceneError> {
    let io_error = |e: std::io::Error| {
        SceneError::new(
            origin,
            ErrorKind::Io,
            format!("cannot read the scene file: {e}"),
        )
        .with_source(e)
    };
    // Follows symbolic links: a link to a regular file is read.
    let metadata = std::fs::metadata(path).map_err(io_error)?;
    if !metadata.is_file() {
        return Err(SceneError::new(
            origin,
            ErrorKind::Io,
            format!(
                "not a regular file but {}: a scene must be a text file",
                kind_of(&metadata.file_type())
            ),
        ));
    }
    let too_large = |size: String| {
        SceneError::new(
            origin,
            ErrorKind::Io,
            format!(
                "the file is {size}, more than the {} MiB a scene file may have",
                MAX_SCENE_BYTES / (1024 * 1024)
            ),
        )
    };
    if metadata.len() > MAX_SCENE_BYTES {
        return Err(too_large(format!("{} bytes", metadata.len())));
    }
    let file = std::fs::File::open(path).map_err(io_error)?;
    let mut bytes = Vec::with_capacity(metadata.len() as usize);
    file.take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io_error)?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(too_large("still growing past the limit".into()));
    }
    decode(origin, &bytes)
}

/// What a non-regular file is, in words.
fn kind_of(file_type: &std::fs::FileType) -> &'static str {
    if file_type.is_dir() {
        return "a folder";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a named pipe (FIFO)";
        }
        if file_type.is_char_device() {
            return "a character device";
        }
        if file_type.is_block_device() {
            return "a block device";
        }
        if file_type.is_socket() {
            return "a socket";
        }
    }
    "a special file"
}

/// Byte-order marks that say the file is not UTF-8, longest first (the
/// UTF-32 little-endian mark starts with UTF-16's).
const FOREIGN_MARKS: [(&[u8], &str); 4] = [
    (&[0xFF, 0xFE, 0x00, 0x00], "UTF-32 little-endian"),
    (&[0x00, 0x00, 0xFE, 0xFF], "UTF-32 big-endian"),
    (&[0xFF, 0xFE], "UTF-16 little-endian"),
    (&[0xFE, 0xFF], "UTF-16 big-endian"),
];

/// Decodes scene bytes as UTF-8, or says what they are instead, located.
pub(crate) fn decode(origin: &str, bytes: &[u8]) -> Result<String, SceneError> {
    let refuse = |position: (usize, usize), message: String| {
        Err(SceneError::new(origin, ErrorKind::Encoding, message).at(Some(position)))
    };
    for (mark, encoding) in FOREIGN_MARKS {
        if bytes.starts_with(mark) {
            let shown: Vec<String> = mark.iter().map(|b| format!("{b:02X}")).collect();
            return refuse(
                (1, 1),
                format!(
                    "the file is {encoding} (byte-order mark {} at its start); a scene file must be UTF-8: save it as UTF-8",
                    shown.join(" ")
                ),
            );
        }
    }
    match std::str::from_utf8(bytes) {
        Ok(text) => {
            if let Some(order) = utf16_without_mark(bytes) {
                return refuse(
                    (1, 1),
                    format!(
                        "the file looks like UTF-16 {order} without a byte-order mark: every other byte is zero; a scene file must be UTF-8: save it as UTF-8"
                    ),
                );
            }
            Ok(text.to_owned())
        }
        Err(e) => {
            let offset = e.valid_up_to();
            let valid = std::str::from_utf8(&bytes[..offset]).unwrap_or_default();
            if let Some(order) = utf16_without_mark(bytes) {
                return refuse(
                    line_column(valid, offset),
                    format!(
                        "the file looks like UTF-16 {order} without a byte-order mark: every other byte is zero; a scene file must be UTF-8: save it as UTF-8"
                    ),
                );
            }
            let byte = bytes[offset];
            let guess = if (0xA0..=0xFF).contains(&byte) {
                let latin1 = char::from(byte);
                format!(
                    " (in Latin-1 / Windows-1252 this byte is '{latin1}': the file was saved in that encoding)"
                )
            } else {
                String::new()
            };
            refuse(
                line_column(valid, offset),
                format!(
                    "invalid UTF-8 at byte {offset}: byte 0x{byte:02X}{guess}; a scene file must be UTF-8: save it as UTF-8"
                ),
            )
        }
    }
}

/// `Some("little-endian")` or `Some("big-endian")` when the first bytes
/// look like UTF-16 text of ASCII characters: zero at every odd (or every
/// even) offset of the first 16 bytes, and nowhere else.
fn utf16_without_mark(bytes: &[u8]) -> Option<&'static str> {
    let head = &bytes[..bytes.len().min(16) & !1];
    if head.len() < 4 {
        return None;
    }
    let zero_at = |parity: usize| {
        head.iter()
            .enumerate()
            .all(|(i, b)| (*b == 0) == (i % 2 == parity))
    };
    if zero_at(1) {
        Some("little-endian")
    } else if zero_at(0) {
        Some("big-endian")
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refused(bytes: &[u8]) -> SceneError {
        decode("s.toml", bytes).unwrap_err()
    }

    #[test]
    fn utf8_passes_and_a_utf8_mark_is_kept_for_toml() {
        assert_eq!(
            decode("s.toml", "a = \"é\"\n".as_bytes()).unwrap(),
            "a = \"é\"\n"
        );
    }

    #[test]
    fn utf16_is_named_with_or_without_its_mark() {
        let mut le = vec![0xFF, 0xFE];
        le.extend("[simulation]".encode_utf16().flat_map(u16::to_le_bytes));
        let e = refused(&le);
        assert_eq!(e.kind(), ErrorKind::Encoding);
        assert!(e.message().contains("UTF-16 little-endian"), "{e}");
        assert!(e.message().contains("FF FE"), "{e}");
        assert_eq!(e.line(), Some(1));
        let be: Vec<u8> = "[simulation]"
            .encode_utf16()
            .flat_map(u16::to_be_bytes)
            .collect();
        let e = refused(&be);
        assert!(e.message().contains("UTF-16 big-endian"), "{e}");
    }

    #[test]
    fn a_latin1_byte_is_located_and_named() {
        let e = refused(b"[simulation]\ndt = 0.1\n# caf\xe9\n");
        assert_eq!((e.line(), e.column()), (Some(3), Some(6)));
        assert!(e.message().contains("byte 27"), "{e}");
        assert!(e.message().contains("0xE9"), "{e}");
        assert!(e.message().contains("'é'"), "{e}");
    }
}
