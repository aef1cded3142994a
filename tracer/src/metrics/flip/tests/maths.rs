//! Each step of FLIP on its own: the colour transforms, the CSF and
//! feature kernels, the feature filters on rows, and the pooling.

use super::super::*;
use super::flat;

fn close(a: Colour, b: Colour, tolerance: f32) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= tolerance)
}

#[test]
fn srgb_decoding_runs_from_0_to_1_and_its_two_pieces_meet() {
    let table = srgb_decoding_table();
    assert_eq!(table[0], 0.0);
    assert!((table[255] - 1.0).abs() < 1e-6, "{}", table[255]);
    assert!(table.windows(2).all(|p| p[0] < p[1]));
    // Mid grey (level 128) is about a fifth of white's light.
    assert!((table[128] - 0.2158605).abs() < 1e-6, "{}", table[128]);
    // The linear piece and the power piece agree where they switch.
    let power = ((0.04045f32 + 0.055) / 1.055).powf(2.4);
    assert!((srgb_to_linear(0.04045) - power).abs() < 1e-6);
}

#[test]
fn white_is_d65_and_lab_puts_white_at_100_and_black_at_0() {
    let white = linear_rgb_to_xyz([1.0; 3]);
    assert!(close(white, D65, 1e-6), "{white:?}");
    assert!(close(xyz_to_lab(white), [100.0, 0.0, 0.0], 1e-4));
    assert!(close(xyz_to_ycxcz(white), [100.0, 0.0, 0.0], 1e-4));
    assert!(close(xyz_to_lab([0.0; 3]), [0.0; 3], 1e-5));
    // YCxCz is linear: black is at -16, not 0.
    assert!(close(xyz_to_ycxcz([0.0; 3]), [-16.0, 0.0, 0.0], 1e-5));
    for c in 0..3 {
        assert!((D65[c] * INV_D65[c] - 1.0).abs() < 1e-7);
    }
}

#[test]
fn colour_transforms_invert_each_other() {
    for rgb in [
        [0.2, 0.5, 0.9],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.01, 0.3, 0.02],
    ] {
        let xyz = linear_rgb_to_xyz(rgb);
        assert!(close(xyz_to_linear_rgb(xyz), rgb, 2e-6), "{rgb:?}");
        assert!(close(ycxcz_to_xyz(xyz_to_ycxcz(xyz)), xyz, 2e-6), "{rgb:?}");
        // Lab and YCxCz share their axes: lightness up, red-green, blue-yellow.
        let (lab, ycxcz) = (xyz_to_lab(xyz), xyz_to_ycxcz(xyz));
        assert!((1..3).all(|c| lab[c].signum() == ycxcz[c].signum() || lab[c].abs() < 1e-3));
    }
    assert!(
        xyz_to_lab(linear_rgb_to_xyz([1.0, 0.0, 0.0]))[1] > 50.0,
        "red is +a"
    );
    assert!(
        xyz_to_lab(linear_rgb_to_xyz([0.0, 0.0, 1.0]))[2] < -50.0,
        "blue is -b"
    );
}

#[test]
fn gamut_clamp_is_the_references_and_sends_nan_to_0() {
    assert_eq!(
        [-0.5, 0.25, 1.5, f32::NAN].map(clamp01),
        [0.0, 0.25, 1.0, 0.0]
    );
}

#[test]
fn hunt_and_hyab() {
    assert_eq!(hunt([0.0, 40.0, -30.0]), [0.0, 0.0, 0.0]);
    assert_eq!(hunt([100.0, 40.0, -30.0]), [100.0, 40.0, -30.0]);
    // City-block in L, Euclidean in a and b.
    assert_eq!(hyab([1.0, 0.0, 0.0], [0.0, 3.0, 4.0]), 6.0);
    assert_eq!(hyab([5.0, 3.0, 4.0], [5.0, 3.0, 4.0]), 0.0);
}

#[test]
fn green_and_blue_are_the_farthest_corners_of_the_gamut() {
    let max = max_colour_distance();
    let corners: Vec<Colour> = (0..8)
        .map(|i| [i & 1, i >> 1 & 1, i >> 2].map(|c| c as f32))
        .collect();
    let lab = |rgb: Colour| hunt(xyz_to_lab(linear_rgb_to_xyz(rgb)));
    for &p in &corners {
        for &q in &corners {
            assert!(hyab(lab(p), lab(q)).powf(GQC) <= max, "{p:?} {q:?}");
        }
    }
    assert!(max > 30.0 && max < 50.0, "{max}");
}

#[test]
fn colour_errors_map_to_0_to_1_in_two_linear_pieces() {
    let max = max_colour_distance();
    let knee = GPC * max;
    assert_eq!(remap_colour(0.0, max), 0.0);
    assert!((remap_colour(knee, max) - GPT).abs() < 1e-6);
    assert!(
        (remap_colour(knee * (1.0 - 1e-6), max) - GPT).abs() < 1e-5,
        "continuous"
    );
    assert!((remap_colour(max, max) - 1.0).abs() < 1e-6);
    // Steeper below the knee: small differences get most of the range.
    assert!(remap_colour(knee / 2.0, max) > GPT / 2.0 - 1e-6);
    assert!(
        remap_colour(knee / 2.0, max)
            > remap_colour(knee, max) - remap_colour(knee / 2.0, max) - 1e-6
    );
    assert_eq!(
        colour_error([50.0, 10.0, -5.0], [50.0, 10.0, -5.0], max),
        0.0
    );
    assert!(
        colour_error([0.0, 0.0, 0.0], [100.0, 0.0, 0.0], max) > GPT,
        "black and white"
    );
}

fn sum(kernel: &[f32]) -> f32 {
    kernel.iter().sum()
}

fn symmetric(kernel: &[f32], sign: f32) -> bool {
    kernel
        .iter()
        .zip(kernel.iter().rev())
        .all(|(a, b)| (a - sign * b).abs() < 1e-7)
}

#[test]
fn csf_kernels_sum_to_1_as_2d_filters() {
    let kernels = csf_kernels(DEFAULT_PIXELS_PER_DEGREE);
    // 3 standard deviations of Cz's widest Gaussian: 9.05 pixels at 67 ppd.
    assert_eq!(csf_radius(DEFAULT_PIXELS_PER_DEGREE), 10);
    for kernel in &kernels {
        assert_eq!(kernel.len(), 21);
        assert!(symmetric(kernel, 1.0));
        // Peaked at the centre, falling off to both sides.
        assert!(kernel[..11].windows(2).all(|p| p[0] <= p[1]));
    }
    let [y, cx, cz1, cz2] = &kernels;
    assert!((sum(y) - 1.0).abs() < 1e-6 && (sum(cx) - 1.0).abs() < 1e-6);
    // Cz's 2D filter, cz1(x) cz1(y) + cz2(x) cz2(y), sums to 1.
    assert!((sum(cz1) * sum(cz1) + sum(cz2) * sum(cz2) - 1.0).abs() < 1e-6);
    // Luminance is seen sharper than colour: Y's kernel is the narrowest.
    assert!(y[10] > cx[10] && y[9] / y[10] < cx[9] / cx[10]);
    // Separable: the product of two taps is the 2D Gaussian of the CSF.
    let delta = 1.0 / DEFAULT_PIXELS_PER_DEGREE;
    for (i, j) in [(1, 0), (2, 3), (4, 4)] {
        let r2 = (i * i + j * j) as f32 * delta * delta;
        let expected = (-PI_SQ * r2 / CSF_B1[0]).exp();
        let product = y[10 + i] * y[10 + j] / (y[10] * y[10]);
        assert!(
            (product - expected).abs() < 1e-5,
            "{i} {j}: {product} {expected}"
        );
    }
    // Fewer pixels per degree: a narrower filter.
    assert!(csf_radius(20.0) < csf_radius(DEFAULT_PIXELS_PER_DEGREE));
}

#[test]
fn feature_kernels_are_a_normalised_gaussian_and_its_derivatives() {
    let [gaussian, first, second] = feature_kernels(DEFAULT_PIXELS_PER_DEGREE);
    // 3 standard deviations of 0.5 x 0.082 degrees: 8.24 pixels at 67 ppd.
    for kernel in [&gaussian, &first, &second] {
        assert_eq!(kernel.len(), 19);
    }
    assert!((sum(&gaussian) - 1.0).abs() < 1e-6);
    assert!(symmetric(&gaussian, 1.0) && symmetric(&first, -1.0) && symmetric(&second, 1.0));
    let signed =
        |k: &[f32], positive: bool| -> f32 { k.iter().filter(|&&v| (v > 0.0) == positive).sum() };
    for kernel in [&first, &second] {
        assert!((signed(kernel, true) - 1.0).abs() < 1e-6);
        assert!((signed(kernel, false) + 1.0).abs() < 1e-6);
    }
    // The first derivative of a bump falls on its right; the second is
    // negative at the top.
    assert_eq!(first[9], 0.0);
    assert!(first[10] < 0.0 && first[8] > 0.0);
    assert!(second[9] < 0.0 && second[0] > 0.0);
}

/// The horizontal planes of row 0 of `image`.
fn horizontal_planes(image: &RgbImage) -> Vec<Vec<f32>> {
    let filters = Filters::new(DEFAULT_PIXELS_PER_DEGREE);
    let w = image.width() as usize;
    let mut channels = Channels::new(w, filters.radius());
    channels.load(image, 0, &srgb_decoding_table());
    let mut out = vec![0.0; PLANES * w];
    channels.filter(&filters, &mut out);
    out.chunks(w).map(<[f32]>::to_vec).collect()
}

#[test]
fn on_a_flat_row_the_filters_keep_the_colour_and_find_no_features() {
    let grey = flat(30, 1, [90; 3]);
    let planes = horizontal_planes(&grey);
    let srgb = srgb_decoding_table();
    let ycxcz = xyz_to_ycxcz(linear_rgb_to_xyz([srgb[90]; 3]));
    let all = |plane: usize, value: f32, tolerance: f32| {
        planes[plane].iter().all(|v| (v - value).abs() < tolerance)
    };
    assert!(all(0, ycxcz[0], 1e-4), "{:?}", planes[0]);
    assert!(all(4, 0.0, 1e-6) && all(5, 0.0, 1e-6));
    assert!(all(6, lightness(ycxcz[0]), 1e-6));
}

#[test]
fn the_edge_detector_answers_at_a_step_and_the_point_detector_at_a_line() {
    let step = RgbImage::from_fn(41, 1, |x, _| image::Rgb([if x < 20 { 0 } else { 255 }; 3]));
    let planes = horizontal_planes(&step);
    let first = &planes[4];
    assert!(first[19].abs() > 0.3 && first[20].abs() > 0.3, "{first:?}");
    assert!(
        first[0].abs() < 1e-6 && first[40].abs() < 1e-6,
        "far from the step"
    );
    let line = RgbImage::from_fn(41, 1, |x, _| image::Rgb([if x == 20 { 255 } else { 0 }; 3]));
    let planes = horizontal_planes(&line);
    let (first, second) = (&planes[4], &planes[5]);
    assert!(first[20].abs() < 1e-6, "no slope on the line itself");
    assert!(second[20] < -0.1 && second[20].abs() > second[15].abs());
}

#[test]
fn edges_pool_towards_1_and_unchanged_features_leave_the_colour_error() {
    assert_eq!(feature_difference((0.3, 0.1), (0.3, 0.1)), 0.0);
    // The larger change counts, scaled by 1 / sqrt(2) and square-rooted.
    assert!((feature_difference((2f32.sqrt(), 0.0), (0.0, 0.5)) - 1.0).abs() < 1e-6);
    assert!((feature_difference((0.0, 0.5), (0.0, 0.0)) - (0.5 / 2f32.sqrt()).sqrt()).abs() < 1e-6);
    for colour in [0.0, 0.01, 0.3, 1.0] {
        assert_eq!(pool(colour, 0.0), colour);
        assert_eq!(pool(colour, 1.0), 1.0);
    }
    assert!(pool(0.1, 0.5) > pool(0.1, 0.2) && pool(0.1, 0.2) > 0.1);
}

#[test]
fn flat_images_of_two_greys_differ_by_their_colour_error_everywhere() {
    let (a, b) = (flat(13, 7, [40; 3]), flat(13, 7, [200; 3]));
    let srgb = srgb_decoding_table();
    let ycxcz = |level: usize| xyz_to_ycxcz(linear_rgb_to_xyz([srgb[level]; 3]));
    let expected = colour_error(ycxcz(40), ycxcz(200), max_colour_distance());
    let errors = error_map(&a, &b, DEFAULT_PIXELS_PER_DEGREE);
    assert_eq!(errors.len(), 13 * 7);
    // No features anywhere: every pixel the same, the colours' error (up to
    // the CSF kernels' rounding).
    assert!(errors.iter().all(|&e| e == errors[0]));
    assert!(
        (errors[0] - expected).abs() < 1e-4,
        "{} {expected}",
        errors[0]
    );
}
