//! SVG to pixels: resvg with the bundled font (no system fonts), so that a picture renders
//! the same on every machine.

use std::path::Path;
use std::sync::OnceLock;

use resvg::{tiny_skia, usvg};

use super::{FONT, FONT_FAMILY, write_file};
use crate::error::{Error, Result};

/// A rendered picture: `width × height` pixels, RGBA (premultiplied alpha), row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct Raster {
    /// Width (px).
    pub width: u32,
    /// Height (px).
    pub height: u32,
    /// `4 · width · height` bytes.
    pub rgba: Vec<u8>,
}

impl Raster {
    /// The pixel at column `x`, row `y` as `[r, g, b, a]`, or `None` outside the picture.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let k = 4 * (y as usize * self.width as usize + x as usize);
        Some([
            self.rgba[k],
            self.rgba[k + 1],
            self.rgba[k + 2],
            self.rgba[k + 3],
        ])
    }
}

/// The options every rendering uses: the bundled font as the only font, and as the default
/// sans-serif family.
fn options() -> &'static usvg::Options<'static> {
    static OPTIONS: OnceLock<usvg::Options<'static>> = OnceLock::new();
    OPTIONS.get_or_init(|| {
        let mut options = usvg::Options::default();
        let fonts = options.fontdb_mut();
        fonts.load_font_data(FONT.to_vec());
        fonts.set_sans_serif_family(FONT_FAMILY);
        options.font_family = FONT_FAMILY.to_owned();
        options
    })
}

fn parse(svg: &str) -> Result<usvg::Tree> {
    usvg::Tree::from_str(svg, options()).map_err(|e| Error::Picture {
        message: format!("the SVG drawn could not be read back for rendering: {e}"),
    })
}

fn pixmap(svg: &str) -> Result<tiny_skia::Pixmap> {
    let tree = parse(svg)?;
    let size = tree.size().to_int_size();
    let mut pixmap =
        tiny_skia::Pixmap::new(size.width(), size.height()).ok_or_else(|| Error::Picture {
            message: format!(
                "a picture of {} × {} pixels cannot be rendered",
                size.width(),
                size.height()
            ),
        })?;
    resvg::render(
        &tree,
        tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    Ok(pixmap)
}

/// Renders an SVG document to pixels at its own size (one pixel per SVG unit).
pub fn render(svg: &str) -> Result<Raster> {
    let pixmap = pixmap(svg)?;
    Ok(Raster {
        width: pixmap.width(),
        height: pixmap.height(),
        rgba: pixmap.data().to_vec(),
    })
}

/// Renders an SVG document and writes it as PNG to `path` (through a temporary file).
pub fn write_png(svg: &str, path: &Path) -> Result<()> {
    let png = pixmap(svg)?.encode_png().map_err(|e| Error::Picture {
        message: format!("PNG encoding failed: {e}"),
    })?;
    write_file(path, &png)
}
