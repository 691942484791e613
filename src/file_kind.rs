//! What a file is by its first bytes, where it is none of the formats swarf reads: the kinds a
//! part or a drawing is most often mistaken for (an image, a PDF, an archive, a STEP or 3MF
//! model), named so that the error says what the file is and what to do, not what a reader
//! made of its bytes ("the binary STL is truncated: it announces 1225588736 triangles" for a
//! PNG renamed `.stl`).

/// A file name's extension, lower-cased ("STL" and "stl" alike), if it has one.
pub fn extension(name: Option<&str>) -> Option<String> {
    name.and_then(|n| n.rsplit_once('.')).map(|(_, e)| e.to_ascii_lowercase())
}

/// A kind of file swarf does not read, known by its signature.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Foreign {
    Png,
    Jpeg,
    Gif,
    Pdf,
    /// A ZIP archive that is no 3MF package.
    Zip,
    /// A 3MF package (a ZIP holding `3D/3dmodel.model`).
    ThreeMf,
    /// A STEP model (ISO 10303-21).
    Step,
}

impl Foreign {
    /// The kind `bytes` are by their signature, if one of these; `name`'s extension tells a 3MF
    /// package whose model is not named near its start.
    pub fn of(name: Option<&str>, bytes: &[u8]) -> Option<Foreign> {
        let ext = extension(name);
        let head = &bytes[..bytes.len().min(4096)];
        let kind = if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            Foreign::Png
        } else if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
            Foreign::Jpeg
        } else if bytes.starts_with(b"GIF87a") || bytes.starts_with(b"GIF89a") {
            Foreign::Gif
        } else if bytes.starts_with(b"%PDF-") {
            Foreign::Pdf
        } else if bytes.starts_with(b"PK\x03\x04") || bytes.starts_with(b"PK\x05\x06") {
            if ext.as_deref() == Some("3mf") || head.windows(16).any(|w| w == b"3D/3dmodel.model") {
                Foreign::ThreeMf
            } else {
                Foreign::Zip
            }
        } else if bytes.trim_ascii_start().starts_with(b"ISO-10303-21") {
            Foreign::Step
        } else {
            return None;
        };
        // A binary STL's 80-byte header may begin with anything: one whose size is exactly
        // its triangles' is an STL whatever its first bytes.
        let binary_stl = bytes.len() >= 84 && {
            let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
            84 + 50 * n == bytes.len() as u64
        };
        (!binary_stl).then_some(kind)
    }

    /// What it is, for a sentence: "a PNG image".
    pub fn describe(self) -> &'static str {
        match self {
            Foreign::Png => "a PNG image",
            Foreign::Jpeg => "a JPEG image",
            Foreign::Gif => "a GIF image",
            Foreign::Pdf => "a PDF document",
            Foreign::Zip => "a ZIP archive",
            Foreign::ThreeMf => "a 3MF package",
            Foreign::Step => "a STEP model (ISO 10303-21)",
        }
    }

    /// What to do instead, when a part was asked for.
    pub fn for_a_part(self) -> &'static str {
        match self {
            Foreign::Png | Foreign::Jpeg | Foreign::Gif | Foreign::Pdf => "export the part from the program that drew it as STL",
            Foreign::Zip => "unpack it and open the part inside",
            Foreign::ThreeMf => "save or export the part as STL",
            Foreign::Step => "export the part from your CAD program as STL",
        }
    }

    /// What to do instead, when a drawing was asked for.
    pub fn for_a_drawing(self) -> &'static str {
        match self {
            Foreign::Png | Foreign::Jpeg | Foreign::Gif => "trace the image into an SVG, or draw it as a DXF",
            Foreign::Pdf => "export the drawing from the program that made it as DXF or SVG",
            Foreign::Zip => "unpack it and open the drawing inside",
            Foreign::ThreeMf | Foreign::Step => "export its outline from your CAD program as DXF or SVG, or machine it as a part (STL)",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signatures_are_named_and_a_binary_stl_of_the_right_size_is_not_taken_for_one() {
        let png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR";
        assert_eq!(Foreign::of(Some("plate.stl"), png), Some(Foreign::Png));
        assert_eq!(Foreign::of(None, b"\xFF\xD8\xFF\xE0\0\x10JFIF"), Some(Foreign::Jpeg));
        assert_eq!(Foreign::of(None, b"%PDF-1.7\n"), Some(Foreign::Pdf));
        assert_eq!(Foreign::of(None, b"PK\x03\x04\x14\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x10\0\0\x003D/3dmodel.model"), Some(Foreign::ThreeMf));
        assert_eq!(Foreign::of(Some("part.3mf"), b"PK\x03\x04"), Some(Foreign::ThreeMf));
        assert_eq!(Foreign::of(Some("parts.zip"), b"PK\x03\x04"), Some(Foreign::Zip));
        assert_eq!(Foreign::of(None, b"  ISO-10303-21;\nHEADER;"), Some(Foreign::Step));
        assert_eq!(Foreign::of(None, b"solid cube\n"), None);
        // A binary STL of one triangle whose header happens to begin like a PNG.
        let mut stl = png.to_vec();
        stl.resize(80, 0);
        stl.extend(1u32.to_le_bytes());
        stl.extend([0u8; 50]);
        assert_eq!(Foreign::of(Some("odd.stl"), &stl), None);
    }
}
