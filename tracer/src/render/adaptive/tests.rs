use glam::Vec3A;

use super::*;
use crate::render::estimate::{Spread, display_value, error_estimate, variance_estimate};
use crate::sampling::stratum_order;

fn settings(threshold: f32, min_spp: u32, max_spp: u32) -> AdaptiveSampling {
    AdaptiveSampling {
        noise_threshold: threshold,
        min_spp,
        max_spp,
        budget: None,
    }
}

/// What a film knows of a pixel whose passes gave it `earlier`, then
/// `last`.
fn spread(earlier: &[f32], last: &[f32]) -> (u32, Spread) {
    let mut spread = Spread::default();
    for (k, &v) in earlier.iter().chain(last).enumerate() {
        if k == earlier.len() {
            spread.earlier = spread.sum;
            spread.earlier_samples = k as u32;
        }
        let v = display_value(Vec3A::splat(v));
        spread.sum += v;
        spread.squares += v * v;
    }
    ((earlier.len() + last.len()) as u32, spread)
}

fn estimate(earlier: &[f32], last: &[f32]) -> f32 {
    let (n, spread) = spread(earlier, last);
    error_estimate(n, &spread)
}

#[test]
fn a_constant_pixel_stops_after_the_minimum() {
    let a = settings(0.01, 8, 64);
    // Zero but for the halves' rounding.
    let error = estimate(&[0.4; 4], &[0.4; 4]);
    assert!(error < 1e-6, "{error}");
    assert!(
        is_active(4, estimate(&[0.4; 2], &[0.4; 2]), 1.0, &a),
        "below the minimum"
    );
    assert!(!is_active(8, error, 1.0, &a));
    // Bright beyond the display's range is as constant as it shows.
    assert_eq!(estimate(&[1.5, 3.0], &[1.0, 2.0]), 0.0);
}

#[test]
fn a_pixel_split_by_an_edge_keeps_refining_until_its_halves_agree() {
    let a = settings(0.01, 8, 64);
    // A quarter of the pixel is a bright object: the first 8 samples
    // see it once, the next 8 three times.
    let first = [0.9, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1];
    let last = [0.9, 0.1, 0.9, 0.1, 0.9, 0.1, 0.1, 0.1];
    let error = estimate(&first, &last);
    // The means differ by 0.2, halves of 8: 0.2 / 2.
    assert!((error - 0.1).abs() < 1e-6, "{error}");
    assert!(is_active(16, error, 1.0, &a));
    assert!(!is_active(64, error, 1.0, &a), "the maximum ends it");
    assert!(!is_active(16, error, 1.0, &settings(0.2, 8, 64)));
    // The error a pixel may keep grows in proportion to its samples:
    // 0.1 keeps refining at 16 against 0.08 (twice 0.04), not at 32
    // (0.16).
    assert!(is_active(16, error, 1.0, &settings(0.04, 8, 64)));
    assert!(!is_active(32, error, 1.0, &settings(0.04, 8, 64)));
    assert_eq!(
        threshold_at(4, 1.0, &settings(0.03, 8, 64)),
        0.03,
        "below the minimum"
    );
    // And to what its samples cost: at 16 a pixel whose samples cost
    // 4 times the average may keep 0.32, one whose cost a quarter of
    // it 0.02.
    assert!(!is_active(16, error, 4.0, &settings(0.04, 8, 64)));
    assert!(is_active(16, error, 0.25, &settings(0.04, 8, 64)));
    // Stratified halves that each see the quarter twice agree: the
    // mean has converged though the samples vary as much as ever.
    let even = [0.9, 0.1, 0.1, 0.1, 0.9, 0.1, 0.1, 0.1];
    assert_eq!(estimate(&even, &even), 0.0);
    let (n, spread) = spread(&even, &even);
    assert!(variance_estimate(n, &spread) > 0.08);
    // Unequal halves weigh the difference by sqrt(a b) / n.
    let unequal = estimate(&[0.5, 0.5], &[0.2; 6]);
    assert!(
        (unequal - 0.3 * 12f32.sqrt() / 8.0).abs() < 1e-6,
        "{unequal}"
    );
}

#[test]
fn one_pass_says_nothing_and_threshold_zero_refines_to_the_maximum() {
    let a = settings(0.5, 1, 16);
    assert!(estimate(&[], &[0.3]).is_infinite());
    assert!(estimate(&[], &[0.3, 0.3]).is_infinite());
    assert!(is_active(1, estimate(&[], &[0.3]), 1.0, &a));
    let zero = settings(0.0, 1, 16);
    assert!(is_active(15, 0.0, 1.0, &zero));
    assert!(!is_active(16, 0.0, 1.0, &zero));
}

#[test]
fn the_schedule_doubles_to_the_minimum_then_to_the_maximum() {
    let a = settings(0.01, 4, 64);
    let mut counts = vec![0];
    // Bounded: a count that stood still would loop here for ever.
    while *counts.last().unwrap() < a.max_spp && counts.len() <= 16 {
        counts.push(next_count(*counts.last().unwrap(), &a));
    }
    assert_eq!(counts, [0, 1, 2, 4, 8, 16, 32, 64]);
    assert_eq!(passes(&a), 7);
    assert_eq!(passes(&settings(0.0, 1, 1)), 1);
    // A minimum or maximum that is not a power of two is met exactly.
    assert_eq!(next_count(4, &settings(0.0, 6, 9)), 6);
    assert_eq!(next_count(6, &settings(0.0, 6, 9)), 9);
}

#[test]
fn early_samples_take_a_prefix_of_light_points_in_proportion_to_power() {
    assert_eq!(early_light_points(3.0, 3.0), 4);
    assert_eq!(early_light_points(0.8, 2.4), 1, "a third of the power");
    assert_eq!(early_light_points(1.5, 3.0), 2);
    assert_eq!(early_light_points(0.0, 3.0), 1, "at least one");
    assert_eq!(early_light_points(0.0, 0.0), 4, "all dark: all alike");
    assert_eq!(early_light_points(f32::INFINITY, f32::INFINITY), 1);
    let a = settings(0.01, 4, 64);
    for early in [1, 2, 4] {
        let ranges: Vec<Range<u32>> = (0..64).map(|k| light_points(k, early, &a)).collect();
        // Each sample's points follow the last's, with no gap.
        assert_eq!(ranges[0].start, 0);
        for pair in ranges.windows(2) {
            assert_eq!(pair[0].end, pair[1].start, "{early}: {pair:?}");
        }
        // The minimum's samples take the first 4 early points, twice
        // the minimum's twice as many; later samples one each.
        assert_eq!(ranges[3].end, 4 * early);
        assert_eq!(ranges[7].end, 8 * early);
        assert!(ranges[8..].iter().all(|r| r.len() == 1));
    }
}

/// A film of `width` x 1 pixels whose passes gave each pixel
/// `earlier[i]`, then `last[i]`.
fn film(pixels: &[(&[f32], &[f32])]) -> Film {
    let mut film = Film::with_error_estimate(pixels.len() as u32, 1);
    for pass in 0..2 {
        let halves: Vec<&[f32]> = pixels
            .iter()
            .map(|p| if pass == 0 { p.0 } else { p.1 })
            .collect();
        add_pass(&mut film, &halves);
    }
    film
}

/// Gives each pixel of `film` (row-major) its samples in `pass`.
fn add_pass(film: &mut Film, pass: &[&[f32]]) {
    // Synthetic samples cost nothing.
    add_costed_pass(film, pass, &vec![0; pass.len()]);
}

/// [`add_pass`] whose pixels made `tests[i]` intersection tests in all.
fn add_costed_pass(film: &mut Film, pass: &[&[f32]], tests: &[u64]) {
    let tile = Tile {
        x: 0,
        y: 0,
        width: film.width(),
        height: film.height(),
    };
    let counts: Vec<u32> = pass.iter().map(|h| h.len() as u32).collect();
    let values: Vec<Vec3A> = pass
        .iter()
        .flat_map(|h| h.iter().map(|&v| Vec3A::splat(v)))
        .collect();
    film.add_samples(&tile, &counts, &values, tests);
}

/// A column of three pixels: an edge A above a flat pixel B above a
/// pixel C whose samples vary but whose halves agree, and the same
/// column upside down. Only A refines after the minimum, and its error
/// grows: B, two rows from C and never sampled again, becomes noisy
/// through A, and C refines for B's sake. A decision that re-pooled only
/// the rows sampled, or decided only the rows it re-pooled (above them
/// as below), would leave both stopped; one that took the rows to
/// re-measure from the film's active pixels would stop A when a budget
/// cut it from a pass.
#[test]
fn a_pass_changes_decisions_two_rows_away_as_a_fresh_decision_does() {
    let a = settings(0.05, 4, 64);
    for upside_down in [false, true] {
        // Rows A, B, C top down, or C, B, A.
        let column = |a: &[f32], b: &[f32], c: &[f32]| -> Vec<Vec<f32>> {
            let mut rows = vec![a.to_vec(), b.to_vec(), c.to_vec()];
            if upside_down {
                rows.reverse();
            }
            rows
        };
        let mut film = Film::with_error_estimate(1, 3);
        let pass = |film: &mut Film, rows: Vec<Vec<f32>>| {
            let rows: Vec<&[f32]> = rows.iter().map(Vec::as_slice).collect();
            add_pass(film, &rows);
        };
        pass(&mut film, column(&[0.5], &[0.3], &[0.9]));
        pass(&mut film, column(&[0.5], &[0.3], &[0.1]));
        pass(&mut film, column(&[0.7, 0.7], &[0.3, 0.3], &[0.1, 0.9]));
        let mut refinement = Refinement::default();
        let first = refinement.decide(&film, &a);
        let only_a: Vec<bool> = column(&[1.0], &[], &[])
            .iter()
            .map(|r| !r.is_empty())
            .collect();
        assert_eq!(first, only_a, "{upside_down}");
        // A budget that cut every pixel from the pass: nothing changed,
        // and A is still above the threshold.
        film.set_active(vec![false; 3]);
        assert_eq!(refinement.decide(&film, &a), first, "{upside_down}");
        film.set_active(first);
        pass(&mut film, column(&[0.0; 4], &[], &[]));
        let second = refinement.decide(&film, &a);
        assert_eq!(second, [true, true, true], "{upside_down}");
        let mean = refinement.mean_per_sample().expect("measured");
        assert_eq!(Refinement::relative_to(mean).decide(&film, &a), second);
    }
}

#[test]
fn a_varying_pixel_next_to_a_noisy_one_refines_too() {
    let a = settings(0.05, 8, 64);
    let edge: (&[f32], &[f32]) = (&[0.9, 0.1, 0.1, 0.1], &[0.9, 0.9, 0.9, 0.1]);
    let lucky: (&[f32], &[f32]) = (&[0.9, 0.1, 0.1, 0.1], &[0.9, 0.1, 0.1, 0.1]);
    let flat: (&[f32], &[f32]) = (&[0.3; 4], &[0.3; 4]);
    let active = Refinement::default().decide(&film(&[edge, lucky, flat, lucky]), &a);
    // The edge on its own account, its lucky neighbour for it; the
    // flat pixel never, the lucky pixel beside it alone stops.
    assert_eq!(active, [true, true, false, false]);
}

#[test]
fn a_round_takes_every_uniform_pass_once_with_stratified_prefixes() {
    for m in [1, 2, 3, 4, 5, 8, 12, 16] {
        let round = RoundOrder::new(m);
        let mut sorted: Vec<u32> = (0..round.len())
            .map(|k| round.pass(k, 0x0007_0009))
            .collect();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..m * m).collect::<Vec<_>>(), "m = {m}");
    }
    // Back to strata: each prefix of 2^j samples of an 8 x 8 round
    // falls once in every box of area 2^-j (columns, rows, blocks),
    // whatever the pixel's random digits.
    let uniform = stratum_order(8);
    let order = RoundOrder::new(8);
    for shift in [0, 0x0005_0003, 0xdead_beef] {
        let strata: Vec<(u32, u32)> = (0..64)
            .map(|k| order.pass(k, shift))
            .map(|p| (uniform[p as usize] % 8, uniform[p as usize] / 8))
            .collect();
        for j in 0..=6u32 {
            let prefix = &strata[..1 << j];
            for a in 0..=j {
                // Boxes 8 / 2^a strata wide, 8 / 2^(j - a) tall.
                let (across, down) = (1u32 << a, 1u32 << (j - a));
                if across > 8 || down > 8 {
                    continue;
                }
                let mut boxes: Vec<u32> = prefix
                    .iter()
                    .map(|&(x, y)| (y * down / 8) * across + x * across / 8)
                    .collect();
                boxes.sort_unstable();
                assert_eq!(
                    boxes,
                    (0..1 << j).collect::<Vec<_>>(),
                    "shift {shift:x}, prefix {}: {across} x {down} boxes",
                    1 << j
                );
            }
        }
    }
    let pattern = |shift| (0..8).map(|k| order.pass(k, shift)).collect::<Vec<_>>();
    assert_ne!(pattern(1), pattern(0x0002_0000), "pixels differ");
}

#[test]
fn a_pixels_digits_move_its_columns_and_rows_apart() {
    // Digits below bit 16 flip the column, those from bit 16 the row:
    // with (1 << 16) | 2, sample k of a 4 x 4 round takes the stratum of
    // the unshifted sample's row ^ 1 and column ^ 2.
    let uniform = stratum_order(4);
    let order = RoundOrder::new(4);
    let stratum = |k, shift| {
        let s = uniform[order.pass(k, shift) as usize];
        (s % 4, s / 4)
    };
    for k in 0..16 {
        let (x, y) = stratum(k, 0);
        assert_eq!(stratum(k, (1 << 16) | 2), (x ^ 2, y ^ 1), "sample {k}");
    }
    for m in [0, 1, 3, 4] {
        let round = RoundOrder::new(m);
        assert_eq!(round.len(), m.max(1) * m.max(1), "m = {m}");
        assert!(!round.is_empty(), "m = {m}: a round takes a sample");
    }
}

#[test]
fn a_pixels_cost_is_its_tests_per_sample_over_the_films() {
    // Two flat pixels, two passes of 2 samples: pixel 0 made 8 tests
    // (2 a sample), pixel 1 none. The film's mean is 1 test a sample and
    // a sample's overhead half of it: costs (2 + 0.5) / 1.5 and
    // 0.5 / 1.5; relative to a mean of 4 (overhead 2), 4 / 6 and 2 / 6.
    let mut film = Film::with_error_estimate(2, 1);
    let tile = Tile {
        x: 0,
        y: 0,
        width: 2,
        height: 1,
    };
    for _ in 0..2 {
        film.add_samples(&tile, &[2, 2], &[Vec3A::splat(0.5); 4], &[4, 0]);
    }
    let a = settings(0.05, 4, 64);
    let costs = |r: &Refinement| [r.relative_cost(0), r.relative_cost(1)];
    let close = |costs: [f32; 2], expected: [f32; 2]| {
        let near = costs
            .iter()
            .zip(expected)
            .all(|(c, e)| (c - e).abs() < 1e-6);
        assert!(near, "{costs:?} against {expected:?}");
    };
    let mut own = Refinement::default();
    own.decide(&film, &a);
    assert_eq!(own.mean_per_sample(), Some(1.0));
    close(costs(&own), [2.5 / 1.5, 0.5 / 1.5]);
    // Flat halves agree: no error anywhere.
    assert_eq!(own.pooled_errors(), &[0.0, 0.0]);
    let mut given = Refinement::relative_to(4.0);
    given.decide(&film, &a);
    assert_eq!(given.mean_per_sample(), Some(4.0));
    close(costs(&given), [4.0 / 6.0, 2.0 / 6.0]);
}

#[test]
fn pixels_past_the_minimum_refine_only_when_noisy() {
    // Flat pixels of 8 samples, above a minimum of 4: no error, nothing
    // refines.
    let flat: (&[f32], &[f32]) = (&[0.3; 4], &[0.3; 4]);
    let a = settings(0.05, 4, 64);
    let mut refinement = Refinement::default();
    assert_eq!(refinement.decide(&film(&[flat, flat]), &a), [false, false]);
    // Given a film of another size, of one row again, it measures every
    // row afresh, not only those its last decision refined (none). The
    // edge's error 0.4 * sqrt(4 * 4) / 8 = 0.2, pooled with two zeros:
    // sqrt((0.2^2 * 8 * 4) / ((3 + 3) * 8)) = 0.163 >= 0.05 * 8 / 4.
    let edge: (&[f32], &[f32]) = (&[0.9, 0.1, 0.1, 0.1], &[0.9, 0.9, 0.9, 0.1]);
    let wider = film(&[flat, edge, flat]);
    assert_eq!(refinement.decide(&wider, &a), [false, true, false]);
}

#[test]
fn a_varying_pixel_at_the_maximum_stops_beside_a_noisy_one() {
    // 8 samples each. The edge's halves have means 0.3 and 0.7: error
    // 0.4 * sqrt(4 * 4) / 8 = 0.2, pooled with the lucky pixel's 0:
    // sqrt((0.2^2 * 8 * 4) / ((2 + 3) * 8)) = 0.179 >= the threshold at
    // 8 samples, 0.05 * 8 / 4 = 0.1: noisy. The lucky pixel's halves
    // agree (error 0), but its samples (two 0.9, six 0.1) vary:
    // sqrt((2 * 0.6^2 + 6 * 0.2^2) / 7 / 8) = 0.131 >= 0.1.
    let edge: (&[f32], &[f32]) = (&[0.9, 0.1, 0.1, 0.1], &[0.9, 0.9, 0.9, 0.1]);
    let lucky: (&[f32], &[f32]) = (&[0.9, 0.1, 0.1, 0.1], &[0.9, 0.1, 0.1, 0.1]);
    let film = film(&[edge, lucky]);
    let below = Refinement::default().decide(&film, &settings(0.05, 4, 16));
    assert_eq!(below, [true, true], "below the maximum both refine");
    let at = Refinement::default().decide(&film, &settings(0.05, 4, 8));
    assert_eq!(at, [false, false], "the maximum ends both");
}

#[test]
fn errors_pool_over_the_window_own_four_times_and_costs_per_pixel() {
    // 2 x 2 pixels, each the others' neighbour. Errors (halves' means
    // apart times sqrt(a b) / n) and tests per sample:
    //   0: 0.5, 0.5 | 0.1, 0.1: 0.4 * 2 / 4 = 0.2, n 4, 3 tests a sample;
    //   1: 0.3 | 0.3: 0, n 2, none;
    //   2: 0.5 x 4 | 0.3 x 4: 0.2 * 4 / 8 = 0.1, n 8, none;
    //   3: 0.7 x 3 | 0.7 x 3: 0, n 6, 1 test a sample.
    let mut film = Film::with_error_estimate(2, 2);
    for (pass, tests) in [
        ([0.5, 0.3, 0.5, 0.7], [6, 0, 0, 3]),
        ([0.1, 0.3, 0.3, 0.7], [6, 0, 0, 3]),
    ] {
        let halves: Vec<Vec<f32>> = [2, 1, 4, 3]
            .iter()
            .zip(pass)
            .map(|(&n, v)| vec![v; n])
            .collect();
        let halves: Vec<&[f32]> = halves.iter().map(Vec::as_slice).collect();
        add_costed_pass(&mut film, &halves, &tests);
    }
    let mut refinement = Refinement::default();
    let active = refinement.decide(&film, &settings(0.05, 2, 64));
    // Each pixel brings e^2 n: 0.16, 0, 0.08, 0; the window sums 0.24
    // over 4 pixels. Pooled: sqrt((0.24 + 3 e^2 n) / ((4 + 3) n)).
    let expected = [
        (0.72f32 / 28.0).sqrt(),
        (0.24f32 / 14.0).sqrt(),
        (0.48f32 / 56.0).sqrt(),
        (0.24f32 / 42.0).sqrt(),
    ];
    let pooled = refinement.pooled_errors();
    let close = pooled
        .iter()
        .zip(expected)
        .all(|(p, e)| (p - e).abs() < 1e-5);
    assert!(
        close && pooled.len() == 4,
        "{pooled:?} against {expected:?}"
    );
    // Tests per sample 3, 0, 0, 1: mean 1, overhead 0.5; costs
    // 3.5 / 1.5, 0.5 / 1.5, 0.5 / 1.5, 1.5 / 1.5.
    assert_eq!(refinement.mean_per_sample(), Some(1.0));
    let costs: Vec<f32> = (0..4).map(|i| refinement.relative_cost(i)).collect();
    let expected = [3.5 / 1.5, 0.5 / 1.5, 0.5 / 1.5, 1.0];
    let close = costs
        .iter()
        .zip(expected)
        .all(|(c, e)| (c - e).abs() < 1e-6);
    assert!(close, "{costs:?} against {expected:?}");
    // Thresholds 0.05 * n / 2 * cost: 0.233, 0.0167, 0.0667, 0.15.
    // Pixels 1 and 2 are above theirs; 0 and 3 below, beside them, but
    // their samples vary less than their thresholds (0's four samples
    // sqrt(4 * 0.2^2 / 3 / 4) = 0.115, 3's none).
    assert_eq!(active, [false, true, true, false]);
}

/// Two pixels of one sample each, below a minimum of 4: both active.
fn below_the_minimum() -> (Film, AdaptiveSampling) {
    let mut film = Film::with_error_estimate(2, 1);
    add_pass(&mut film, &[&[0.5], &[0.5]]);
    (film, settings(0.01, 4, 64))
}

#[test]
fn the_strategy_expects_its_schedule_and_at_least_one_pass_more() {
    let (mut film, a) = below_the_minimum();
    let mut strategy = Adaptive::new(a);
    // 0, 1, 2, 4, 8, 16, 32, 64 samples: 7 passes, before any decision.
    assert_eq!(strategy.passes_target(), 7);
    // After pass 1 (the second), pixels still active: at least pass 2,
    // 3 passes in all, whatever the target said.
    let mut stats = RenderStats::default();
    let end = strategy.end_pass(1, &mut film, &mut stats, false);
    assert_eq!((end, stats.passes_target), (PassEnd::More, 3));
    assert_eq!(stats.adaptive.map(|s| s.active_pixels), Some(2));
    // A budget the driver saw spent ends it there, pixels left active.
    let end = strategy.end_pass(1, &mut film, &mut stats, true);
    assert_eq!((end, stats.passes_target), (PassEnd::Done, 2));
    assert_eq!(stats.adaptive.map(|s| s.active_pixels), Some(2));
}

#[test]
fn a_budget_refines_the_largest_errors_that_fit() {
    // 3 x 2 pixels of 2 + 2 samples, each halves' means apart by d: an
    // error of d * sqrt(2 * 2) / 4 = d / 2, here 0.05, 0, 0.4 over 0.1,
    // 0.3, 0.
    let mut film = Film::with_error_estimate(3, 2);
    add_pass(
        &mut film,
        &[
            &[0.5; 2], &[0.3; 2], &[0.9; 2], &[0.5; 2], &[0.8; 2], &[0.6; 2],
        ],
    );
    add_pass(
        &mut film,
        &[
            &[0.4; 2], &[0.3; 2], &[0.1; 2], &[0.3; 2], &[0.2; 2], &[0.6; 2],
        ],
    );
    let a = settings(0.0, 4, 64);
    let all = vec![true; 6];
    // 24 samples taken, 4 more each to 8: 48 fits every pixel.
    assert_eq!(
        within_budget(&film, all.clone(), &a, 48),
        (all.clone(), false)
    );
    // 32 fits two: the largest errors, (2, 0) and (1, 1).
    let cut = within_budget(&film, all, &a, 32);
    assert_eq!(cut, (vec![false, false, true, false, true, false], true));
}

#[test]
fn the_summary_counts_every_pixel_and_the_rms_of_the_measured_errors() {
    // Pixel 0: 2 + 2 samples, halves 0.5 and 0.1, error 0.4 * 2 / 4 =
    // 0.2; pixel 1: 1 + 1, flat, 0; pixel 2: one pass, not measured.
    let mut film = Film::with_error_estimate(3, 1);
    add_pass(&mut film, &[&[0.5, 0.5], &[0.3], &[]]);
    add_pass(&mut film, &[&[0.1, 0.1], &[0.3], &[0.7]]);
    film.set_active(vec![true, false, true]);
    let stats = summary(&film);
    assert_eq!(
        (
            stats.pixels,
            stats.samples,
            stats.max_spp,
            stats.active_pixels
        ),
        (3, 7, 4, 2)
    );
    // sqrt((0.2^2 + 0^2) / 2).
    let rms = 0.02f32.sqrt();
    assert!((stats.error - rms).abs() < 1e-6, "{stats:?}");
    // No pixel measured: infinite, not 0 / 0.
    let (film, _) = below_the_minimum();
    assert_eq!(summary(&film).error, f32::INFINITY);
}
