//! What a study's points say: the best point of each structure (the
//! fastest value, or for `spp` the knee of error against time) and, for the
//! level study, how frame time grows with the scene (the slope on log-log
//! axes).

use tracer::accel::AccelKind;

use super::{Param, Point};

/// The structures of `points`, in the order they first appear.
pub(crate) fn structures(points: &[Point]) -> Vec<AccelKind> {
    let mut found = Vec::new();
    for p in points {
        if !found.contains(&p.accel()) {
            found.push(p.accel());
        }
    }
    found
}

/// The points of one structure, by ascending x.
pub(crate) fn series(points: &[Point], accel: AccelKind) -> Vec<&Point> {
    let mut series: Vec<&Point> = points.iter().filter(|p| p.accel() == accel).collect();
    series.sort_by(|a, b| a.x.total_cmp(&b.x));
    series
}

/// The neighbouring points of the first structure between which `count`
/// falls the most, if it falls anywhere: where a material study's rays
/// change most (refraction lost to total internal reflection).
pub(crate) fn steepest_fall(
    points: &[Point],
    count: impl Fn(&Point) -> u64,
) -> Option<(&Point, &Point)> {
    let accel = *structures(points).first()?;
    let series = series(points, accel);
    series
        .windows(2)
        .map(|pair| (pair[0], pair[1]))
        .filter(|(a, b)| count(b) < count(a))
        .max_by_key(|(a, b)| count(a) - count(b))
}

/// Why a point is marked best.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Best {
    /// The shortest median frame time of its structure.
    Fastest,
    /// The knee of error against time: past it, more samples buy little.
    Knee,
}

/// The best point of each structure (indices into `points`): for grid-m
/// the grid's fastest m (m changes nothing else), for `spp` and
/// `noise-threshold` the knee of error against time. Other parameters have none: their fastest value is
/// the cheapest image (no bounce, a pinhole), not a choice to recommend;
/// the level study has its slopes instead (see [`slope`]).
pub(crate) fn best(param: Param, points: &[Point]) -> Vec<(usize, Best)> {
    structures(points)
        .into_iter()
        .filter_map(|accel| {
            let mine = || {
                points
                    .iter()
                    .enumerate()
                    .filter(|(_, p)| p.accel() == accel)
            };
            match param {
                Param::GridM if accel == AccelKind::Grid => mine()
                    .min_by(|(_, a), (_, b)| a.frame_ms().total_cmp(&b.frame_ms()))
                    .map(|(i, _)| (i, Best::Fastest)),
                Param::Spp | Param::NoiseThreshold => {
                    let curve: Vec<(usize, f64, f64)> = mine()
                        .filter_map(|(i, p)| Some((i, p.frame_ms(), p.error?.mse)))
                        .collect();
                    knee(&curve).map(|i| (i, Best::Knee))
                }
                _ => None,
            }
        })
        .collect()
}

/// The knee of a falling curve of (id, time, error): the point farthest
/// below the chord from the fastest to the slowest point, on axes scaled
/// to 0..1. `None` with fewer than three points or no bend.
fn knee(curve: &[(usize, f64, f64)]) -> Option<usize> {
    if curve.len() < 3 {
        return None;
    }
    let range = |values: Vec<f64>| {
        let low = values.iter().copied().fold(f64::INFINITY, f64::min);
        let high = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (low, (high - low).max(f64::MIN_POSITIVE))
    };
    let (t0, tspan) = range(curve.iter().map(|c| c.1).collect());
    let (e0, espan) = range(curve.iter().map(|c| c.2).collect());
    let mut sorted: Vec<(usize, f64, f64)> = curve
        .iter()
        .map(|&(i, t, e)| (i, (t - t0) / tspan, (e - e0) / espan))
        .collect();
    sorted.sort_by(|a, b| a.1.total_cmp(&b.1));
    let (first, last) = (sorted[0], sorted[sorted.len() - 1]);
    // How far below the chord (positive) each point lies.
    let below = |&(_, t, e): &(usize, f64, f64)| {
        let (dt, de) = (last.1 - first.1, last.2 - first.2);
        (dt * (first.2 - e) + de * (t - first.1)) / dt.hypot(de).max(f64::MIN_POSITIVE)
    };
    sorted
        .iter()
        .filter(|c| below(c) > 1e-9)
        .max_by(|a, b| below(a).total_cmp(&below(b)))
        .map(|c| c.0)
}

/// The least-squares slope of log(frame time) against log(x) for one
/// structure: 1 means time grows in proportion to the scene, 0 means it
/// does not grow. `None` with fewer than two distinct positive x.
pub(crate) fn slope(points: &[Point], accel: AccelKind) -> Option<f64> {
    let logs: Vec<(f64, f64)> = series(points, accel)
        .iter()
        .filter(|p| p.x > 0.0 && p.frame_ms() > 0.0)
        .map(|p| (p.x.ln(), p.frame_ms().ln()))
        .collect();
    let n = logs.len() as f64;
    let mean_x = logs.iter().map(|l| l.0).sum::<f64>() / n;
    let mean_y = logs.iter().map(|l| l.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|l| (l.0 - mean_x).powi(2)).sum();
    let sxy: f64 = logs.iter().map(|l| (l.0 - mean_x) * (l.1 - mean_y)).sum();
    (logs.len() >= 2 && sxx > 1e-12).then(|| sxy / sxx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_knee_is_where_the_curve_bends() {
        // Error halves as time doubles: the bend is at the second point.
        let curve = [
            (0, 1.0, 100.0),
            (1, 2.0, 20.0),
            (2, 4.0, 10.0),
            (3, 8.0, 5.0),
        ];
        assert_eq!(knee(&curve), Some(1));
        // A straight line has no knee; two points have none either.
        assert_eq!(knee(&[(0, 1.0, 3.0), (1, 2.0, 2.0), (2, 3.0, 1.0)]), None);
        assert_eq!(knee(&curve[..2]), None);
    }
}
