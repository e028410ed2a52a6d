//! Writing a figure: its formats (SVG, PNG at a stated resolution, PDF with the font
//! embedded), its size, and the one SVG that every format is rendered from.

use super::{err, put_fine_lines, register_font, Figure, FINE_LINES};
use crate::{Error, Result};
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// A file format of figures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FigureFormat {
    /// Vector, text as text (DejaVu Sans).
    Svg,
    /// Raster at [`FigureOptions::dpi`].
    Png,
    /// Vector, the font embedded: for a paper.
    Pdf,
}

impl FigureFormat {
    fn extension(self) -> &'static str {
        match self {
            FigureFormat::Svg => "svg",
            FigureFormat::Png => "png",
            FigureFormat::Pdf => "pdf",
        }
    }
}

/// How figures are written: which formats, at which size, the PNG at which resolution.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureOptions {
    /// The formats written, each to `<name>.<extension>`.
    pub formats: Vec<FigureFormat>,
    /// Width and height in CSS pixels (96 to the inch); `None`: each figure's own. The
    /// layout (text sizes, margins) stays in pixels, so a smaller figure has larger text
    /// relative to it, as a figure for a narrow column should.
    pub size_px: Option<(u32, u32)>,
    /// Resolution of the PNG (dots per inch): 300 by default, as journals ask for print;
    /// 96 draws one dot per CSS pixel (a screen).
    pub dpi: u32,
}

impl Default for FigureOptions {
    fn default() -> Self {
        Self {
            formats: vec![FigureFormat::Svg, FigureFormat::Png],
            size_px: None,
            dpi: 300,
        }
    }
}

impl FigureOptions {
    /// Smallest and largest side of a figure (CSS pixels): below it the axes' labels
    /// do not fit; above it, a poster.
    pub const SIDE_PX: std::ops::RangeInclusive<u32> = 320..=6000;
    /// Accepted PNG resolutions (dpi).
    pub const DPI: std::ops::RangeInclusive<u32> = 24..=1200;

    /// Checks the settings, naming the bad one.
    pub fn validate(&self) -> Result<()> {
        if self.formats.is_empty() {
            return Err(Error::Input("figure formats: none given".into()));
        }
        if let Some((w, h)) = self.size_px {
            for (name, v) in [("width", w), ("height", h)] {
                if !Self::SIDE_PX.contains(&v) {
                    return Err(Error::Input(format!(
                        "figure {name} {v} px is out of range: expected {} to {} px",
                        Self::SIDE_PX.start(),
                        Self::SIDE_PX.end()
                    )));
                }
            }
        }
        if !Self::DPI.contains(&self.dpi) {
            return Err(Error::Input(format!(
                "figure resolution {} dpi is out of range: expected {} to {}",
                self.dpi,
                Self::DPI.start(),
                Self::DPI.end()
            )));
        }
        Ok(())
    }
}

/// The font database of the PNG and PDF renderers: the embedded DejaVu Sans, standing for
/// every family the SVG names.
fn font_options() -> &'static resvg::usvg::Options<'static> {
    static OPTIONS: OnceLock<resvg::usvg::Options<'static>> = OnceLock::new();
    OPTIONS.get_or_init(|| {
        let mut options = resvg::usvg::Options::default();
        let db = options.fontdb_mut();
        db.load_font_data(dejavu::sans::regular().to_vec());
        db.set_sans_serif_family("DejaVu Sans");
        options.font_family = "DejaVu Sans".into();
        options
    })
}

/// RGBA pixels as PNG bytes that declare their resolution (`pHYs`), so that a word
/// processor places them at their size in inches.
fn png_bytes(rgba: &[u8], w: u32, h: u32, dpi: u32) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, w, h);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let per_metre = (f64::from(dpi) / 0.0254).round() as u32;
    encoder.set_pixel_dims(Some(png::PixelDimensions {
        xppu: per_metre,
        yppu: per_metre,
        unit: png::Unit::Meter,
    }));
    let mut writer = encoder.write_header().map_err(err)?;
    writer.write_image_data(rgba).map_err(err)?;
    writer.finish().map_err(err)?;
    Ok(bytes)
}

/// Renders `fig` once as SVG and writes it in every format of `options` to
/// `<base>.<extension>`; returns the paths. The PNG and PDF are the SVG rendered (resvg,
/// svg2pdf), so the three show the same figure.
pub fn save(fig: &impl Figure, base: &Path, options: &FigureOptions) -> Result<Vec<PathBuf>> {
    options.validate()?;
    register_font()?;
    let size = options.size_px.unwrap_or_else(|| fig.size());
    let mut svg = String::new();
    FINE_LINES.with(|f| *f.borrow_mut() = Some(Vec::new()));
    let drawn = {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        fig.draw(&root).and_then(|()| root.present().map_err(err))
    };
    let lines = FINE_LINES
        .with(|f| f.borrow_mut().take())
        .unwrap_or_default();
    drawn?;
    let svg = put_fine_lines(&svg, &lines)?;
    let tree = || resvg::usvg::Tree::from_str(&svg, font_options()).map_err(err);
    let mut files = Vec::new();
    for &format in &options.formats {
        let path = base.with_extension(format.extension());
        let bytes = match format {
            FigureFormat::Svg => svg.clone().into_bytes(),
            FigureFormat::Png => {
                let scale = options.dpi as f32 / 96.0;
                let (w, h) = (
                    (size.0 as f32 * scale).round() as u32,
                    (size.1 as f32 * scale).round() as u32,
                );
                let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h)
                    .ok_or_else(|| Error::Figure(format!("cannot allocate {w}×{h} pixels")))?;
                pixmap.fill(resvg::tiny_skia::Color::WHITE);
                resvg::render(
                    &tree()?,
                    resvg::tiny_skia::Transform::from_scale(scale, scale),
                    &mut pixmap.as_mut(),
                );
                // Opaque (white behind everything), so premultiplied RGBA is plain RGBA.
                png_bytes(pixmap.data(), w, h, options.dpi)?
            }
            FigureFormat::Pdf => svg2pdf::to_pdf(
                &tree()?,
                svg2pdf::ConversionOptions::default(),
                svg2pdf::PageOptions { dpi: 96.0 },
            )
            .map_err(err)?,
        };
        crate::files::write_file(&path, &bytes)?;
        files.push(path);
    }
    Ok(files)
}
