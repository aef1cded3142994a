//! The accumulation buffer: a running sum of samples per pixel, resolved on
//! demand to an 8-bit image.

use glam::{DVec3, Vec3A};
use rayon::prelude::*;

use super::Encoding;
use super::estimate::{Spread, display_value, error_estimate};

/// A rectangle of pixels rendered as one unit of work.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tile {
    /// Left column, in pixels.
    pub x: u32,
    /// Top row, in pixels.
    pub y: u32,
    /// Width in pixels; edge tiles may be narrower than [`TILE_SIZE`](super::TILE_SIZE).
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Tile {
    /// Splits a `width` x `height` image into tiles of at most `size` pixels
    /// a side, row by row.
    pub fn grid(width: u32, height: u32, size: u32) -> Vec<Tile> {
        let size = size.max(1);
        let mut tiles = Vec::new();
        for y in (0..height).step_by(size as usize) {
            for x in (0..width).step_by(size as usize) {
                tiles.push(Tile {
                    x,
                    y,
                    width: size.min(width - x),
                    height: size.min(height - y),
                });
            }
        }
        tiles
    }

    pub(crate) fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Copies the tile's RGB bytes (`rgb`, row-major within the tile) into
    /// `image`, row-major RGB bytes of an image `image_width` wide.
    pub(crate) fn copy_rgb_into(&self, image_width: u32, rgb: &[u8], image: &mut [u8]) {
        let pixels: &[[u8; 3]] = bytemuck::cast_slice(rgb);
        let image: &mut [[u8; 3]] = bytemuck::cast_slice_mut(image);
        for (start, row) in self.rows(image_width, pixels) {
            image[start..start + row.len()].copy_from_slice(row);
        }
    }

    /// The tile's rows of `values` (row-major within the tile), each with
    /// the index of its first pixel in an image `image_width` wide.
    pub fn rows<'a, T>(
        &self,
        image_width: u32,
        values: &'a [T],
    ) -> impl Iterator<Item = (usize, &'a [T])> {
        let (x, y) = (self.x as usize, self.y as usize);
        values
            .chunks(self.width.max(1) as usize)
            .enumerate()
            .map(move |(row, chunk)| ((y + row) * image_width as usize + x, chunk))
    }
}

/// Pixels a task resolves at once.
const BAND: usize = 32 * 1024;

/// Per-pixel sums of linear radiance and sample counts.
#[derive(Debug, Clone, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    /// In f64: n equal f32 samples then sum and divide exactly, so a flat
    /// pixel's mean is its samples' value whatever n (in f32, 0.3 summed 8
    /// or 16 times fell on either side of 76.5 levels, and adaptive and
    /// uniform renders of one flat sky differed by a level everywhere).
    sum: Vec<DVec3>,
    samples: Vec<u32>,
    /// Per pixel, what adaptive sampling's error estimate needs, the
    /// estimate itself, and the intersection tests the pixel's samples
    /// made (what they cost); empty unless made with
    /// [`Film::with_error_estimate`]. The estimates and tests are kept
    /// apart from the spreads, 64 bytes a pixel: the decision between
    /// passes reads them over the whole film, and reading the spreads
    /// instead (17 MB at 512 x 512) took it milliseconds a pass.
    spread: Vec<Spread>,
    errors: Vec<f32>,
    tests: Vec<u64>,
    /// Adaptive sampling: the pixels the next pass refines, set by
    /// [`Film::set_active`] between passes; empty otherwise.
    active: Vec<bool>,
}

impl Film {
    /// A film with no sample yet. Its memory comes zeroed from the
    /// allocator, lazily: no page is touched until `Film::prefault` or a
    /// first sample, so making even a large film is instant.
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            sum: bytemuck::allocation::zeroed_vec(n),
            samples: vec![0; n],
            spread: Vec::new(),
            errors: Vec::new(),
            tests: Vec::new(),
            active: Vec::new(),
        }
    }

    /// A film that also estimates each pixel's error ([`Film::error`]).
    pub fn with_error_estimate(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self {
            spread: vec![Spread::default(); n],
            errors: vec![f32::INFINITY; n],
            tests: vec![0; n],
            active: vec![true; n],
            ..Self::new(width, height)
        }
    }

    /// Writes the film's zeros into its pages, so that the render's adds,
    /// which read before they write, find real pages. A lazily zeroed page
    /// faults twice under an add, the second time copying the shared zero
    /// page and flushing the other cores' TLBs by interrupt (perf:
    /// `do_wp_page`, `flush_tlb_mm_range`). Done once, by whoever has a
    /// spare core: a job does it while its structure builds.
    pub(crate) fn prefault(&mut self) {
        self.sum.fill(DVec3::ZERO);
        self.samples.fill(0);
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Adds one sample to each pixel of `tile`; `values` is row-major
    /// within the tile.
    pub(crate) fn add_tile(&mut self, tile: &Tile, values: &[Vec3A]) {
        for (start, chunk) in tile.rows(self.width, values) {
            if self.spread.is_empty() {
                let sums = &mut self.sum[start..start + chunk.len()];
                for (s, v) in sums.iter_mut().zip(chunk) {
                    *s += v.as_dvec3();
                }
                for n in &mut self.samples[start..start + chunk.len()] {
                    *n += 1;
                }
            } else {
                for (i, v) in (start..).zip(chunk) {
                    self.add(i, *v);
                    self.estimate_error(i);
                }
            }
        }
    }

    /// Adds samples to the pixels of `tile`: `counts` says how many each
    /// pixel (row-major within the tile) takes, `values` holds them pixel
    /// after pixel, each pixel's in the order they were taken, and
    /// `tests` the intersection tests each pixel's samples made (one entry
    /// a pixel, as `counts`).
    pub(crate) fn add_samples(
        &mut self,
        tile: &Tile,
        counts: &[u32],
        values: &[Vec3A],
        tests: &[u64],
    ) {
        debug_assert_eq!(tests.len(), counts.len(), "one test count a pixel");
        let mut values = values.iter();
        let mut tests = tests.iter();
        for (start, row) in tile.rows(self.width, counts) {
            for (i, &count) in (start..).zip(row) {
                let pixel_tests = tests.next().copied().unwrap_or(0);
                if count == 0 {
                    continue;
                }
                if let Some(spread) = self.spread.get_mut(i) {
                    spread.earlier = spread.sum;
                    spread.earlier_samples = self.samples[i];
                    self.tests[i] += pixel_tests;
                }
                for v in values.by_ref().take(count as usize) {
                    self.add(i, *v);
                }
                self.estimate_error(i);
            }
        }
    }

    /// Adds one sample to pixel `i`.
    #[inline]
    fn add(&mut self, i: usize, v: Vec3A) {
        self.sum[i] += v.as_dvec3();
        self.samples[i] += 1;
        if let Some(spread) = self.spread.get_mut(i) {
            let shown = display_value(v);
            spread.sum += shown;
            spread.squares += shown * shown;
        }
    }

    /// Brings pixel `i`'s error estimate up to date with its samples.
    #[inline]
    fn estimate_error(&mut self, i: usize) {
        if let Some(spread) = self.spread.get(i) {
            self.errors[i] = error_estimate(self.samples[i], spread);
        }
    }

    /// Samples pixel `(x, y)` has taken.
    pub fn samples(&self, x: u32, y: u32) -> u32 {
        self.samples[y as usize * self.width as usize + x as usize]
    }

    /// The error of pixel `(x, y)`'s mean estimated from its samples, in
    /// display units (see [`super::estimate::error_estimate`]); infinite
    /// when the film does not estimate it or before two passes gave it
    /// samples.
    pub fn error(&self, x: u32, y: u32) -> f32 {
        self.errors
            .get(y as usize * self.width as usize + x as usize)
            .copied()
            .unwrap_or(f32::INFINITY)
    }

    /// Every pixel's sample count, row-major: what adaptive sampling's
    /// decision over the whole film reads without a lookup per pixel.
    pub(crate) fn sample_counts(&self) -> &[u32] {
        &self.samples
    }

    /// Every pixel's [`Spread`], row-major; empty when the film does not
    /// estimate errors.
    pub(crate) fn spreads(&self) -> &[Spread] {
        &self.spread
    }

    /// Every pixel's error estimate ([`Film::error`]), row-major; empty
    /// when the film does not estimate errors.
    pub(crate) fn errors(&self) -> &[f32] {
        &self.errors
    }

    /// The intersection tests each pixel's samples made, row-major; empty
    /// when the film does not estimate errors.
    pub(crate) fn tests(&self) -> &[u64] {
        &self.tests
    }

    /// What adaptive sampling knows of pixel `(x, y)`'s samples; `None`
    /// when the film does not estimate errors.
    pub fn spread(&self, x: u32, y: u32) -> Option<&Spread> {
        self.spread
            .get(y as usize * self.width as usize + x as usize)
    }

    /// Whether the next adaptive pass refines pixel `(x, y)`: every pixel
    /// before [`Film::set_active`] first runs; never when the film does
    /// not estimate errors.
    pub fn is_active(&self, x: u32, y: u32) -> bool {
        self.active
            .get(y as usize * self.width as usize + x as usize)
            .copied()
            .unwrap_or(false)
    }

    /// Which pixels the next adaptive pass refines, row-major (see
    /// [`Film::is_active`]); `None` when the film does not estimate
    /// errors. What a viewer draws over the image while it refines.
    pub fn active_pixels(&self) -> Option<&[bool]> {
        (!self.spread.is_empty()).then_some(self.active.as_slice())
    }

    /// Sets which pixels the next pass refines (row-major): decided
    /// between passes, over the whole film, so that a pixel may look at
    /// its neighbours and still not depend on the order tiles ran in.
    pub fn set_active(&mut self, active: Vec<bool>) {
        debug_assert_eq!(active.len(), self.samples.len());
        self.active = active;
    }

    /// The mean radiance of pixel `(x, y)`, `None` before its first sample.
    pub fn pixel(&self, x: u32, y: u32) -> Option<Vec3A> {
        let i = y as usize * self.width as usize + x as usize;
        let n = *self.samples.get(i)?;
        (n > 0).then(|| (self.sum[i] / f64::from(n)).as_vec3a())
    }

    /// Resolves the film to RGBA8, row-major from the top-left. Pixels with
    /// no sample yet are transparent black. On the calling thread alone:
    /// a viewer's call, which may come from a thread that must not wait
    /// for a pool (a web page's main thread).
    pub fn to_rgba8(&self, encoding: Encoding) -> Vec<u8> {
        let mut out = vec![0; self.sum.len() * 4];
        for (band, out) in out.chunks_mut(BAND * 4).enumerate() {
            self.resolve_band::<4>(band, out, encoding);
        }
        out
    }

    /// Resolves the film to an RGB image, a band of rows per task on the
    /// current pool.
    pub fn to_image(&self, encoding: Encoding) -> image::RgbImage {
        let mut out = vec![0; self.sum.len() * 3];
        out.par_chunks_mut(BAND * 3)
            .enumerate()
            .for_each(|(band, out)| self.resolve_band::<3>(band, out, encoding));
        image::RgbImage::from_raw(self.width, self.height, out)
            .expect("the buffer holds exactly width * height pixels")
    }

    /// Band `band`'s pixels of `CHANNELS` bytes (3: RGB, 4: RGBA with an
    /// opaque alpha), black for pixels with no sample.
    fn resolve_band<const CHANNELS: usize>(&self, band: usize, out: &mut [u8], encoding: Encoding) {
        for (k, pixel) in out.chunks_exact_mut(CHANNELS).enumerate() {
            let i = band * BAND + k;
            if self.samples[i] == 0 {
                continue;
            }
            pixel[..3].copy_from_slice(&self.resolve_pixel(i, encoding));
            if CHANNELS == 4 {
                pixel[3] = u8::MAX;
            }
        }
    }

    /// Writes `tile`'s pixels, resolved as [`Film::to_image`] resolves
    /// them, into `rgb`, a row-major RGB buffer of the whole film.
    pub(crate) fn resolve_tile(&self, tile: &Tile, encoding: Encoding, rgb: &mut [u8]) {
        for y in tile.y..tile.y + tile.height {
            let start = y as usize * self.width as usize + tile.x as usize;
            let end = start + tile.width as usize;
            let pixels = rgb[start * 3..end * 3].chunks_exact_mut(3);
            for (pixel, i) in pixels.zip(start..end) {
                pixel.copy_from_slice(&self.resolve_pixel(i, encoding));
            }
        }
    }

    /// Pixel `i`'s bytes, black before its first sample; after one sample
    /// the bytes [`encode_values`] gives that sample.
    #[inline]
    fn resolve_pixel(&self, i: usize, encoding: Encoding) -> [u8; 3] {
        match self.samples[i] {
            0 => [0; 3],
            // One sample, the first pass: the sum is the mean.
            1 => encoding.encode_rgb(self.sum[i].as_vec3a()),
            n => encoding.encode_rgb((self.sum[i] / f64::from(n)).as_vec3a()),
        }
    }

    /// The mean linear radiance of every pixel as floats, before any
    /// clamping or encoding (for OpenEXR output); black before a pixel's
    /// first sample.
    pub fn to_linear_image(&self) -> image::Rgb32FImage {
        image::Rgb32FImage::from_fn(self.width, self.height, |x, y| {
            image::Rgb(self.pixel(x, y).unwrap_or_default().to_array())
        })
    }
}

/// Drops the alpha of a row-major RGBA8 buffer: the form images are saved
/// in. `None` when the buffer does not hold `width * height` pixels.
pub fn rgba_to_rgb_image(width: u32, height: u32, rgba: &[u8]) -> Option<image::RgbImage> {
    let rgb: Vec<u8> = rgba
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    image::RgbImage::from_raw(width, height, rgb)
}

/// One sample per pixel, `values`, as RGB bytes: what a film resolves
/// them to after its first pass (the sum of one sample is the sample).
pub(super) fn encode_values(values: &[Vec3A], encoding: Encoding) -> Vec<u8> {
    values
        .iter()
        .flat_map(|&v| encoding.encode_rgb(v))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_cover_the_image_once() {
        let tiles = Tile::grid(70, 33, 16);
        let mut covered = vec![0u8; 70 * 33];
        for t in &tiles {
            for y in t.y..t.y + t.height {
                for x in t.x..t.x + t.width {
                    covered[(y * 70 + x) as usize] += 1;
                }
            }
        }
        assert!(covered.iter().all(|&c| c == 1));
    }

    #[test]
    fn film_averages_samples() {
        let mut film = Film::new(4, 2);
        let tile = Tile {
            x: 2,
            y: 1,
            width: 2,
            height: 1,
        };
        film.add_tile(&tile, &[Vec3A::ONE, Vec3A::ZERO]);
        film.add_tile(&tile, &[Vec3A::ZERO, Vec3A::ZERO]);
        assert_eq!(film.pixel(2, 1), Some(Vec3A::splat(0.5)));
        assert_eq!(film.pixel(0, 0), None);
        let rgba = film.to_rgba8(Encoding::Linear);
        assert_eq!(&rgba[(4 + 2) * 4..(4 + 2) * 4 + 4], &[128, 128, 128, 255]);
        assert_eq!(&rgba[0..4], &[0, 0, 0, 0]);
        let rgb = film.to_image(Encoding::Linear);
        assert_eq!(rgb.get_pixel(2, 1).0, [128, 128, 128]);
        assert_eq!(rgb.get_pixel(0, 0).0, [0, 0, 0]);
        assert_eq!(rgb.as_raw().len(), 4 * 2 * 3);
    }

    /// The tile of pixel `(x, y)` alone.
    fn one_pixel(x: u32, y: u32) -> Tile {
        Tile {
            x,
            y,
            width: 1,
            height: 1,
        }
    }

    /// A 4 x 3 film whose pixel `i` (row-major) took `i + 1` samples of
    /// value `i / 16` in one pass, with `10 i` intersection tests: every
    /// pixel told apart by each of them.
    fn numbered(film: &mut Film) {
        let tile = Tile {
            x: 0,
            y: 0,
            width: 4,
            height: 3,
        };
        let counts: Vec<u32> = (1..=12).collect();
        let values: Vec<Vec3A> = (0..12u8)
            .flat_map(|i| {
                std::iter::repeat_n(Vec3A::splat(f32::from(i) / 16.0), usize::from(i) + 1)
            })
            .collect();
        let tests: Vec<u64> = (0..12).map(|i| 10 * i).collect();
        film.add_samples(&tile, &counts, &values, &tests);
    }

    #[test]
    fn tiles_are_cut_at_the_right_and_bottom_edges() {
        let tiles = Tile::grid(70, 33, 16);
        assert_eq!(tiles.len(), 5 * 3);
        let tile = |x, y, width, height| Tile {
            x,
            y,
            width,
            height,
        };
        assert_eq!(tiles[0], tile(0, 0, 16, 16));
        assert_eq!(tiles[4], tile(64, 0, 6, 16));
        assert_eq!(tiles[14], tile(64, 32, 6, 1));
        assert_eq!(tiles[14].pixel_count(), 6);
        assert_eq!(tile(0, 0, 3, 5).pixel_count(), 15);
    }

    #[test]
    fn a_tiles_rows_start_where_the_image_holds_them() {
        // Tile at (2, 1), 2 x 2, in an image 5 wide: rows start at
        // 1 * 5 + 2 and 2 * 5 + 2.
        let tile = Tile {
            x: 2,
            y: 1,
            width: 2,
            height: 2,
        };
        let rows: Vec<_> = tile.rows(5, &[1, 2, 3, 4]).collect();
        assert_eq!(rows, [(7, &[1, 2][..]), (12, &[3, 4][..])]);

        let mut image = vec![0u8; 5 * 3 * 3];
        tile.copy_rgb_into(5, &[1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4], &mut image);
        let mut expected = vec![0u8; 5 * 3 * 3];
        for (pixel, value) in [(7, 1), (8, 2), (12, 3), (13, 4)] {
            expected[pixel * 3..pixel * 3 + 3].fill(value);
        }
        assert_eq!(image, expected);
    }

    #[test]
    fn an_estimating_film_starts_unknown_and_active() {
        let plain = Film::new(4, 3);
        assert_eq!((plain.width(), plain.height()), (4, 3));
        assert_eq!(plain.active_pixels(), None);
        assert!(!plain.is_active(0, 0));
        assert_eq!(plain.error(1, 1), f32::INFINITY);
        assert_eq!(plain.spread(1, 1), None);

        let film = Film::with_error_estimate(4, 3);
        assert_eq!(film.sample_counts(), &[0; 12]);
        assert_eq!(film.spreads(), &[Spread::default(); 12]);
        assert_eq!(film.errors(), &[f32::INFINITY; 12]);
        assert_eq!(film.tests(), &[0; 12]);
        assert_eq!(film.active_pixels(), Some(&[true; 12][..]));
    }

    #[test]
    fn each_pixel_is_found_at_its_own_place() {
        let mut film = Film::with_error_estimate(4, 3);
        numbered(&mut film);
        let counts: Vec<u32> = (1..=12).collect();
        assert_eq!(film.sample_counts(), counts);
        let tests: Vec<u64> = (0..12).map(|i| 10 * i).collect();
        assert_eq!(film.tests(), tests);
        let mut active = vec![false; 12];
        active[9] = true;
        film.set_active(active.clone());
        assert_eq!(film.active_pixels(), Some(&active[..]));
        for y in 0..3 {
            for x in 0..4 {
                let i = y * 4 + x;
                assert_eq!(film.samples(x, y), i + 1, "({x}, {y})");
                assert_eq!(film.pixel(x, y), Some(Vec3A::splat(i as f32 / 16.0)));
                assert_eq!(film.is_active(x, y), i == 9, "({x}, {y})");
                let spread = film.spread(x, y).expect("an estimating film");
                assert_eq!(spread.sum, Vec3A::splat((i + 1) as f32 * i as f32 / 16.0));
                assert_eq!(film.error(x, y), f32::INFINITY, "one pass");
            }
        }
        // A second pass for pixel (1, 2) alone, equal to its first: its
        // halves agree, so its error is zero, every other one unknown.
        let tile = one_pixel(1, 2);
        film.add_samples(&tile, &[1], &[Vec3A::splat(9.0 / 16.0)], &[0]);
        for y in 0..3 {
            for x in 0..4 {
                let expected = if (x, y) == (1, 2) { 0.0 } else { f32::INFINITY };
                assert_eq!(film.error(x, y), expected, "({x}, {y})");
            }
        }
    }

    #[test]
    fn samples_keep_their_display_spread_and_error() {
        // One pixel, two passes: 0.25 and 2.0 (shown clamped to 1), then
        // 0.5 twice. Display sum 1.25 + 1, squares 0.0625 + 1 + 2 x 0.25.
        let tile = one_pixel(0, 0);
        let mut film = Film::with_error_estimate(1, 1);
        film.add_samples(&tile, &[2], &[Vec3A::splat(0.25), Vec3A::splat(2.0)], &[7]);
        assert_eq!(film.error(0, 0), f32::INFINITY, "one pass");
        film.add_samples(&tile, &[0], &[], &[100]);
        assert_eq!(film.samples(0, 0), 2, "a pixel given no sample");
        assert_eq!(film.tests(), &[7], "its tests are not counted");
        film.add_samples(&tile, &[2], &[Vec3A::splat(0.5); 2], &[5]);
        let spread = film.spread(0, 0).unwrap();
        assert_eq!(spread.sum, Vec3A::splat(2.25));
        assert_eq!(spread.squares, Vec3A::splat(1.5625));
        assert_eq!(spread.earlier, Vec3A::splat(1.25));
        assert_eq!(spread.earlier_samples, 2);
        assert_eq!(film.tests(), &[12]);
        // Halves' means 0.625 and 0.5: difference 0.125, times
        // sqrt(2 * 2) / 4.
        assert_eq!(film.error(0, 0), 0.0625);
        assert_eq!(film.errors(), &[0.0625]);
        // The radiance itself is not clamped: (0.25 + 2 + 0.5 + 0.5) / 4.
        assert_eq!(film.pixel(0, 0), Some(Vec3A::splat(0.8125)));
    }

    #[test]
    fn a_whole_pass_on_an_estimating_film_updates_its_error() {
        // Two passes of one sample each: 1 then 0.5, halves differ by
        // 0.5, times sqrt(1 * 1) / 2.
        let tile = one_pixel(1, 0);
        let mut film = Film::with_error_estimate(2, 1);
        film.add_tile(&tile, &[Vec3A::ONE]);
        film.add_samples(&tile, &[1], &[Vec3A::splat(0.5)], &[0]);
        assert_eq!(film.samples(1, 0), 2);
        assert_eq!(film.samples(0, 0), 0);
        assert_eq!(film.error(1, 0), 0.25);
        assert_eq!(film.spread(1, 0).unwrap().squares, Vec3A::splat(1.25));
    }

    #[test]
    fn a_resolved_tile_holds_the_films_bytes_and_nothing_else() {
        let mut film = Film::new(4, 3);
        numbered(&mut film);
        let image = film.to_image(Encoding::Linear);
        let tile = Tile {
            x: 1,
            y: 1,
            width: 2,
            height: 2,
        };
        let mut rgb = vec![7u8; 4 * 3 * 3];
        film.resolve_tile(&tile, Encoding::Linear, &mut rgb);
        for y in 0..3 {
            for x in 0..4 {
                let i = (y * 4 + x) as usize;
                let inside = (1..3).contains(&x) && (1..3).contains(&y);
                // Pixel i's mean is i / 16: i * 255 / 16 levels, rounded.
                let level = ((i * 255) as f32 / 16.0).round() as u8;
                let expected = if inside { [level; 3] } else { [7; 3] };
                assert_eq!(rgb[i * 3..i * 3 + 3], expected, "({x}, {y})");
                assert_eq!(image.get_pixel(x, y).0, [level; 3], "({x}, {y})");
            }
        }
        assert_eq!(
            encode_values(
                &[Vec3A::splat(0.5), Vec3A::new(0.0, 1.0, 2.0)],
                Encoding::Linear
            ),
            [128, 128, 128, 0, 255, 255]
        );
    }

    #[test]
    fn images_are_the_pixels_means() {
        let mut film = Film::new(4, 3);
        numbered(&mut film);
        let linear = film.to_linear_image();
        assert_eq!(linear.dimensions(), (4, 3));
        assert_eq!(linear.get_pixel(2, 1).0, [6.0 / 16.0; 3]);
        let rgba = film.to_rgba8(Encoding::Linear);
        let rgb = rgba_to_rgb_image(4, 3, &rgba).expect("4 x 3 pixels");
        assert_eq!(rgb, film.to_image(Encoding::Linear));
        // Pixel 11's mean, 11 / 16, is 175.3 levels.
        assert_eq!(rgba[11 * 4..], [175, 175, 175, 255]);
        assert_eq!(rgba_to_rgb_image(4, 4, &rgba), None, "12 pixels for 16");
    }

    #[test]
    fn a_film_of_several_bands_resolves_each_pixel_in_its_place() {
        // 256 x 160 pixels, more than one band (BAND): pixel (x, y) is
        // x / 255 red and y / 255 green, so its bytes are x and y.
        let (width, height) = (256, 160);
        assert!((width * height) as usize > BAND);
        let values: Vec<Vec3A> = (0..height)
            .flat_map(|y| (0..width).map(move |x| Vec3A::new(x as f32, y as f32, 0.0) / 255.0))
            .collect();
        let mut film = Film::new(width, height);
        let whole = Tile {
            x: 0,
            y: 0,
            width,
            height,
        };
        film.add_tile(&whole, &values);
        let rgba = film.to_rgba8(Encoding::Linear);
        let rgb = film.to_image(Encoding::Linear);
        assert_eq!(rgba.len(), (width * height * 4) as usize);
        for y in 0..height {
            for x in 0..width {
                let i = (y * width + x) as usize;
                let (r, g) = (x as u8, y as u8);
                assert_eq!(rgba[i * 4..i * 4 + 4], [r, g, 0, 255], "({x}, {y})");
                assert_eq!(rgb.get_pixel(x, y).0, [r, g, 0], "({x}, {y})");
            }
        }
    }
}
