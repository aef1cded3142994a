//! Text in the charts, measured and drawn in Rust with egui's embedded
//! font (ab_glyph), the same on the desktop and on the web page. plotters
//! on wasm32 measures and draws text through the browser's document,
//! which the Web Workers that run studies lack; [`EmbeddedText`] wraps a
//! drawing backend so that every text that reaches the backend is laid
//! out and rasterized here, and [`legend`] draws the series legend, which
//! plotters measures through its font without the backend.

use std::sync::OnceLock;

use ab_glyph::{Font, FontRef, ScaleFont};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::Pos;
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontFamily,
    FontStyle, FontTransform,
};

/// The chart font could not be read (the embedded bytes are not a font).
#[derive(Debug, Clone, Copy, thiserror::Error)]
#[error("the embedded chart font cannot be read")]
pub(crate) struct FontUnreadable;

/// egui's embedded sans-serif font, parsed once.
fn font() -> Result<&'static FontRef<'static>, FontUnreadable> {
    static FONT: OnceLock<Option<FontRef<'static>>> = OnceLock::new();
    FONT.get_or_init(|| FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).ok())
        .as_ref()
        .ok_or(FontUnreadable)
}

/// The box `text` takes at `size` pixels: its advance (kerning included)
/// wide, and as high as plotters' own measure says (an em at 1.24 line
/// spacing), so the charts keep the layout they had on the desktop.
pub(crate) fn text_box(text: &str, size: f64) -> Result<(i32, i32), FontUnreadable> {
    let font = font()?.as_scaled(size as f32);
    let mut width = 0.0;
    let mut previous = None;
    for c in text.chars() {
        let glyph = font.glyph_id(c);
        if let Some(previous) = previous {
            width += font.kern(previous, glyph);
        }
        width += font.h_advance(glyph);
        previous = Some(glyph);
    }
    Ok((width as i32, (size / 1.24) as i32))
}

/// Rasterizes `text` at `size` pixels with its top left at `(0, 0)` (the
/// baseline half a size down), calling `pixel` with each covered pixel
/// and its coverage (0 to 1).
fn rasterize<E>(
    text: &str,
    size: f64,
    mut pixel: impl FnMut(i32, i32, f32) -> Result<(), E>,
) -> Result<Result<(), E>, FontUnreadable> {
    let font = font()?.as_scaled(size as f32);
    let mut pen = 0.0;
    let mut previous = None;
    for c in text.chars() {
        let glyph = font.glyph_id(c);
        if let Some(previous) = previous {
            pen += font.kern(previous, glyph);
        }
        if let Some(outline) = font.outline_glyph(font.scaled_glyph(c)) {
            let bounds = outline.px_bounds();
            let (dx, dy) = (pen as i32, (size as f32 / 2.0 + bounds.min.y) as i32);
            let mut covered = Vec::new();
            outline.draw(|x, y, coverage| covered.push((x, y, coverage)));
            for (x, y, coverage) in covered {
                if let Err(e) = pixel(x as i32 + dx, y as i32 + dy, coverage) {
                    return Ok(Err(e));
                }
            }
        }
        pen += font.h_advance(glyph);
        previous = Some(glyph);
    }
    Ok(Ok(()))
}

/// A text style as the caller gave it (colour, size, anchor, rotation),
/// measured and drawn with the embedded font.
struct Embedded<'a, S>(&'a S);

impl<S: BackendTextStyle> BackendTextStyle for Embedded<'_, S> {
    type FontError = FontUnreadable;

    fn color(&self) -> BackendColor {
        self.0.color()
    }

    fn size(&self) -> f64 {
        self.0.size()
    }

    fn transform(&self) -> FontTransform {
        self.0.transform()
    }

    fn style(&self) -> FontStyle {
        self.0.style()
    }

    fn anchor(&self) -> Pos {
        self.0.anchor()
    }

    fn family(&self) -> FontFamily<'_> {
        self.0.family()
    }

    fn layout_box(&self, text: &str) -> Result<((i32, i32), (i32, i32)), FontUnreadable> {
        Ok(((0, 0), text_box(text, self.size())?))
    }

    fn draw<E, DrawFunc: FnMut(i32, i32, BackendColor) -> Result<(), E>>(
        &self,
        text: &str,
        (x, y): BackendCoord,
        mut draw: DrawFunc,
    ) -> Result<Result<(), E>, FontUnreadable> {
        let colour = self.color();
        rasterize(text, self.size(), |px, py, coverage| {
            let alpha = colour.alpha * f64::from(coverage);
            draw(x + px, y + py, BackendColor { alpha, ..colour })
        })
    }
}

/// A drawing backend whose text is the embedded font's: everything else
/// goes to `B` as it is.
pub(crate) struct EmbeddedText<B>(pub B);

impl<B: DrawingBackend> DrawingBackend for EmbeddedText<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.present()
    }

    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        colour: BackendColor,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_pixel(point, colour)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_rect(upper_left, bottom_right, style, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_path(path, style)
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        centre: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_circle(centre, radius, style, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vertices: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.fill_polygon(vertices, style)
    }

    fn blit_bitmap(
        &mut self,
        at: BackendCoord,
        size: (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.blit_bitmap(at, size, src)
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        at: BackendCoord,
    ) -> Result<(), DrawingErrorKind<B::ErrorType>> {
        self.0.draw_text(text, &Embedded(style), at)
    }

    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
    ) -> Result<(u32, u32), DrawingErrorKind<B::ErrorType>> {
        self.0.estimate_text_size(text, &Embedded(style))
    }
}

/// The series legend of a chart's plotting `area`: a box at `position`,
/// a line of `style`'s text for each of `lines` (a name and its colour)
/// with a short stroke of that colour before it, placed as plotters'
/// own legend places them.
pub(crate) fn legend<B: DrawingBackend>(
    area: &DrawingArea<B, Shift>,
    lines: &[(&str, RGBColor)],
    position: &SeriesLabelPosition,
    style: &TextStyle,
    box_style: (ShapeStyle, ShapeStyle),
) -> Result<(), DrawingAreaErrorKind<B::ErrorType>> {
    const MARGIN: i32 = 10;
    const STROKE_AREA: i32 = 30;
    let size = BackendTextStyle::size(style);
    let font_error = |e: FontUnreadable| {
        DrawingAreaErrorKind::BackendError(DrawingErrorKind::FontError(Box::new(e)))
    };
    // Each line's top (1.25 sizes apart) and text box.
    let mut laid_out = Vec::with_capacity(lines.len());
    for (i, (name, _)) in lines.iter().enumerate() {
        let top = (i as f64 * size * 1.25).round() as i32;
        laid_out.push((top, text_box(name, size).map_err(font_error)?));
    }
    let (w, h) = laid_out.iter().fold((0, 0), |(w, h), &(top, (dx, dy))| {
        (w.max(dx), h.max(top + dy))
    });
    let (w, h) = (w + STROKE_AREA + 2 * MARGIN, h + 2 * MARGIN);
    let (x, y) = legend_corner(position, (w, h), area.dim_in_pixel());
    let (background, border) = box_style;
    let corners = [(x, y), (x + w, y + h)];
    area.draw(&Rectangle::new(corners, background))?;
    area.draw(&Rectangle::new(corners, border))?;
    let text_x = x + STROKE_AREA + MARGIN;
    for ((name, _), &(top, _)) in lines.iter().zip(&laid_out) {
        area.draw(&Text::new(*name, (text_x, y + MARGIN + top), style.clone()))?;
    }
    for ((_, colour), &(top, (_, dy))) in lines.iter().zip(&laid_out) {
        let (sx, sy) = (x + MARGIN, y + MARGIN + top + dy / 2);
        let stroke = vec![(sx, sy), (sx + 20, sy)];
        area.draw(&PathElement::new(stroke, Color::stroke_width(colour, 2)))?;
    }
    Ok(())
}

/// The top left corner of a legend `size` big at `position` in an area
/// `area` big: 5 pixels in from the edges it names.
fn legend_corner(
    position: &SeriesLabelPosition,
    (w, h): (i32, i32),
    (area_w, area_h): (u32, u32),
) -> (i32, i32) {
    use SeriesLabelPosition::*;
    let (area_w, area_h) = (area_w as i32, area_h as i32);
    let x = match position {
        UpperLeft | MiddleLeft | LowerLeft => 5,
        UpperMiddle | MiddleMiddle | LowerMiddle => (area_w - w) / 2,
        UpperRight | MiddleRight | LowerRight => area_w - w - 5,
        Coordinate(x, _) => *x,
    };
    let y = match position {
        UpperLeft | UpperMiddle | UpperRight => 5,
        MiddleLeft | MiddleMiddle | MiddleRight => (area_h - h) / 2,
        LowerLeft | LowerMiddle | LowerRight => area_h - h - 5,
        Coordinate(_, y) => *y,
    };
    (x, y)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Draws into a white `w` x `h` image through [`EmbeddedText`];
    /// returns its pixels.
    fn drawn(
        (w, h): (u32, u32),
        draw: impl FnOnce(&DrawingArea<EmbeddedText<BitMapBackend>, Shift>),
    ) -> Vec<[u8; 3]> {
        let mut buffer = vec![0u8; (w * h * 3) as usize];
        {
            let area =
                EmbeddedText(BitMapBackend::with_buffer(&mut buffer, (w, h))).into_drawing_area();
            area.fill(&WHITE).unwrap();
            draw(&area);
            area.present().unwrap();
        }
        buffer.chunks(3).map(|p| [p[0], p[1], p[2]]).collect()
    }

    /// The x and y extent of the pixels darker than mid grey.
    fn ink(pixels: &[[u8; 3]], w: usize) -> Option<((usize, usize), (usize, usize))> {
        let dark: Vec<(usize, usize)> = (pixels.iter().enumerate())
            .filter(|(_, p)| p.iter().all(|&c| c < 128))
            .map(|(i, _)| (i % w, i / w))
            .collect();
        let xs = dark.iter().map(|d| d.0);
        let ys = dark.iter().map(|d| d.1);
        Some((
            (xs.clone().min()?, xs.max()?),
            (ys.clone().min()?, ys.max()?),
        ))
    }

    #[test]
    fn text_is_drawn_as_wide_as_it_measures() {
        let (text, size) = ("frame time (ms)", 20.0);
        let (width, height) = text_box(text, size).unwrap();
        assert_eq!(height, 16);
        assert!(text_box("frame time (ms), median", size).unwrap().0 > width);
        assert_eq!(text_box("", size).unwrap(), (0, 16));
        let pixels = drawn((300, 60), |area| {
            let style = ("sans-serif", size).into_font().color(&BLACK);
            area.draw(&Text::new(text, (10, 20), style)).unwrap();
        });
        let ((left, right), (top, bottom)) = ink(&pixels, 300).expect("no text drawn");
        let inked = (right + 1 - left) as i32;
        assert!((width - 4..=width).contains(&inked), "{inked} of {width}");
        // Capitals and parentheses reach above the top it was drawn at,
        // as plotters' own font drew them; nothing falls far below.
        assert!((10..20).contains(&top) && bottom < 45, "{top}..{bottom}");
    }

    #[test]
    fn turned_text_runs_up_the_image() {
        let pixels = drawn((60, 300), |area| {
            let style = ("sans-serif", 16)
                .into_font()
                .transform(FontTransform::Rotate270)
                .color(&BLACK);
            area.draw(&Text::new("frame time (ms)", (30, 250), style))
                .unwrap();
        });
        let ((left, right), (top, bottom)) = ink(&pixels, 60).expect("no text drawn");
        assert!(
            bottom - top > 4 * (right - left),
            "{left}..{right} x {top}..{bottom}"
        );
        assert!(bottom <= 250, "{bottom}");
    }

    #[test]
    fn a_legend_names_each_line_beside_its_colour() {
        let colours = [RGBColor(52, 120, 198), RGBColor(46, 160, 67)];
        let (w, h) = (300, 200);
        let pixels = drawn((w, h), |area| {
            let style = ("sans-serif", 15).into_text_style(area);
            let lines = [("grid", colours[0]), ("bvh", colours[1])];
            let boxed = (WHITE.filled(), BLACK.into());
            legend(
                area,
                &lines,
                &SeriesLabelPosition::UpperRight,
                &style,
                boxed,
            )
            .unwrap();
        });
        for RGBColor(r, g, b) in colours {
            assert!(pixels.contains(&[r, g, b]), "no stroke of {r},{g},{b}");
        }
        // The box's border and the names are all in its corner.
        let ((left, right), (top, bottom)) = ink(&pixels, w as usize).unwrap();
        assert_eq!((right, top), (w as usize - 5, 5));
        assert!(
            left > 200 && bottom < 80,
            "{left}..{right} x {top}..{bottom}"
        );
    }

    #[test]
    fn legends_go_five_pixels_in_from_the_edges_they_name() {
        use SeriesLabelPosition::*;
        let at = |position| legend_corner(&position, (100, 40), (500, 300));
        assert_eq!(at(UpperLeft), (5, 5));
        assert_eq!(at(UpperMiddle), (200, 5));
        assert_eq!(at(UpperRight), (395, 5));
        assert_eq!(at(MiddleRight), (395, 130));
        assert_eq!(at(LowerLeft), (5, 255));
        assert_eq!(at(Coordinate(7, 9)), (7, 9));
    }
}
