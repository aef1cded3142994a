//! Render settings and counts in human words: a one-line label for a
//! benchmark row, what differs between two settings to label the sides of
//! an A/B comparison ("grid on, m = 4" against "no acceleration"), a
//! count with a metric suffix and a time in milliseconds. Measurements label their cases with these
//! and reports print them, so they live below both.

use std::time::Duration;

use tracer::accel::AccelKind;
use tracer::render::{Budget, RenderSettings};
use tracer::scene::Viewpoint;

/// One thing the settings control, said briefly and in detail. The detail
/// is shown only when two settings agree briefly but still differ (two soft
/// shadows of different light sizes), so labels stay short.
struct Aspect {
    brief: String,
    detailed: String,
}

impl Aspect {
    fn plain(text: String) -> Self {
        Self {
            brief: text.clone(),
            detailed: text,
        }
    }
}

/// Whether N changes the image: it stratifies pixels with AA, the lens
/// with DOF and area lights with soft shadows; one hard-shadowed sample per
/// pixel ignores it.
fn samples_matter(s: &RenderSettings) -> bool {
    s.antialiasing || s.depth_of_field || s.soft_shadows
}

/// The aspects of `s` rendering `view` (whose lens it sees through unless
/// `s` overrides it) in a fixed order, the same for any settings, so two
/// lists compare element by element. The first four are the features the
/// workbench is about (see [`describe`]). `show_n` asks to mention N even
/// without AA (when it matters to either side of a comparison).
fn aspects(s: &RenderSettings, view: &Viewpoint, show_n: bool) -> Vec<Aspect> {
    let n = s.samples;
    let accel = match s.accel {
        AccelKind::None => "no acceleration".to_string(),
        AccelKind::Grid => format!("grid on, m = {}", s.grid_multiplier),
        AccelKind::Bvh => "BVH".to_string(),
    };
    let sampling = if let Some(a) = s.adaptive().filter(|_| s.antialiasing) {
        // A budget (compare's B at A's cost) is part of what B is.
        let budget = match a.budget {
            Some(Budget::Samples(n)) => format!(", at most {n} samples"),
            Some(Budget::Time(t)) => format!(", at most {:.3} s", t.as_secs_f64()),
            None => String::new(),
        };
        Aspect {
            brief: format!("adaptive AA, threshold {}{budget}", a.noise_threshold),
            detailed: format!(
                "adaptive AA, threshold {}, {} to {} spp{budget}",
                a.noise_threshold, a.min_spp, a.max_spp
            ),
        }
    } else if s.antialiasing {
        Aspect::plain(format!("AA {n}x{n}"))
    } else {
        Aspect {
            brief: "no AA".into(),
            detailed: if show_n {
                format!("no AA, N = {n}")
            } else {
                "no AA".into()
            },
        }
    };
    let shadows = if !s.shadows {
        Aspect::plain("no shadows".into())
    } else if s.soft_shadows {
        Aspect {
            brief: "soft shadows on".into(),
            detailed: format!("soft shadows on, light size {}", s.light_size),
        }
    } else {
        Aspect::plain("hard shadows".into())
    };
    let dof = match s.lens(view) {
        Some(lens) => format!("DOF aperture {} focal {}", lens.aperture, lens.focal),
        None => "no DOF".into(),
    };
    let camera = match &s.camera {
        None => Aspect::plain("scene camera".into()),
        Some(pose) => Aspect {
            brief: "moved camera".into(),
            detailed: format!(
                "camera at ({}, {}, {})",
                pose.from.x, pose.from.y, pose.from.z
            ),
        },
    };
    vec![
        Aspect::plain(accel),
        sampling,
        shadows,
        Aspect::plain(dof),
        Aspect::plain(format!("{}x{}", s.width, s.height)),
        Aspect::plain(format!("depth {}", s.max_depth)),
        Aspect::plain(format!("ambient {}", s.ambient)),
        Aspect::plain(format!("seed {}", s.seed)),
        camera,
        Aspect::plain(
            if s.keep_refining {
                "refining past N x N"
            } else {
                "stops at N x N"
            }
            .into(),
        ),
    ]
}

/// The features of `s` rendering `view` the workbench compares (structure,
/// anti-aliasing, shadows, depth of field) in one line, e.g. "BVH, AA 4x4,
/// hard shadows, no DOF".
pub(crate) fn describe(s: &RenderSettings, view: &Viewpoint) -> String {
    aspects(s, view, false)
        .into_iter()
        .take(4)
        .map(|a| a.brief)
        .collect::<Vec<_>>()
        .join(", ")
}

/// One aspect on which two settings differ, as each side has it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Difference {
    pub(crate) a: String,
    pub(crate) b: String,
}

/// What differs between `a` and `b`, rendering `views` (a side's lens is
/// its view's unless its settings override it), in the order of the
/// settings panel; empty when they render the same image.
pub(crate) fn differences(
    a: &RenderSettings,
    b: &RenderSettings,
    views: [&Viewpoint; 2],
) -> Vec<Difference> {
    let show_n = samples_matter(a) || samples_matter(b);
    aspects(a, views[0], show_n)
        .into_iter()
        .zip(aspects(b, views[1], show_n))
        .filter_map(|(x, y)| {
            if x.brief != y.brief {
                Some(Difference {
                    a: x.brief,
                    b: y.brief,
                })
            } else if x.detailed != y.detailed {
                Some(Difference {
                    a: x.detailed,
                    b: y.detailed,
                })
            } else {
                None
            }
        })
        .collect()
}

/// Labels for the two sides of a comparison: each side's differences
/// joined, or "same settings" for both when nothing differs.
pub(crate) fn side_labels(
    a: &RenderSettings,
    b: &RenderSettings,
    views: [&Viewpoint; 2],
) -> (String, String) {
    let diffs = differences(a, b, views);
    if diffs.is_empty() {
        return ("same settings".into(), "same settings".into());
    }
    let join =
        |side: fn(&Difference) -> &str| diffs.iter().map(side).collect::<Vec<_>>().join(", ");
    (join(|d| &d.a), join(|d| &d.b))
}

/// A count with a metric suffix: 1234567 -> "1.23M".
pub(crate) fn si(n: f64) -> String {
    match n {
        n if n >= 1e9 => format!("{:.2}G", n / 1e9),
        n if n >= 1e6 => format!("{:.2}M", n / 1e6),
        n if n >= 1e3 => format!("{:.1}k", n / 1e3),
        n => format!("{n:.0}"),
    }
}

/// A duration in milliseconds, the unit every time the workbench shows is
/// in (window, tables, reports).
pub(crate) fn millis(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

#[cfg(test)]
mod tests {
    use super::*;
    use tracer::render::LensOverride;
    use tracer::scene::Lens;

    /// A pinhole's view: the tests' lenses are the settings' own.
    static VIEW: std::sync::LazyLock<Viewpoint> = std::sync::LazyLock::new(Viewpoint::default);

    fn base() -> RenderSettings {
        RenderSettings {
            accel: AccelKind::None,
            ..RenderSettings::default()
        }
    }

    #[test]
    fn identical_settings_have_no_differences() {
        assert!(differences(&base(), &base(), [&VIEW; 2]).is_empty());
        assert_eq!(
            side_labels(&base(), &base(), [&VIEW; 2]),
            ("same settings".into(), "same settings".into())
        );
    }

    #[test]
    fn each_feature_is_named_in_words() {
        let b = RenderSettings {
            accel: AccelKind::Grid,
            grid_multiplier: 4.0,
            antialiasing: true,
            samples: 4,
            soft_shadows: true,
            depth_of_field: true,
            lens_override: LensOverride::all(Lens {
                aperture: 8.0,
                focal: 1.5,
            }),
            ..base()
        };
        let (la, lb) = side_labels(&base(), &b, [&VIEW; 2]);
        assert_eq!(la, "no acceleration, no AA, hard shadows, no DOF");
        assert_eq!(
            lb,
            "grid on, m = 4, AA 4x4, soft shadows on, DOF aperture 8 focal 1.5"
        );
        assert_eq!(describe(&b, &VIEW), lb);
        let adaptive = RenderSettings {
            sampling: tracer::render::Sampling::Adaptive(
                tracer::render::AdaptiveSampling::for_samples(4, 0.02),
            ),
            ..b.clone()
        };
        let (_, la) = side_labels(&b, &adaptive, [&VIEW; 2]);
        assert_eq!(la, "adaptive AA, threshold 0.02");
        let (_, detailed) = side_labels(
            &adaptive,
            &RenderSettings {
                sampling: tracer::render::Sampling::Adaptive(
                    tracer::render::AdaptiveSampling::for_samples(5, 0.02),
                ),
                ..adaptive.clone()
            },
            [&VIEW; 2],
        );
        assert_eq!(detailed, "adaptive AA, threshold 0.02, 6 to 100 spp");
        let mut budgeted = adaptive.clone();
        if let tracer::render::Sampling::Adaptive(a) = &mut budgeted.sampling {
            a.budget = Some(Budget::Samples(4096));
        }
        let (_, lb) = side_labels(&adaptive, &budgeted, [&VIEW; 2]);
        assert_eq!(lb, "adaptive AA, threshold 0.02, at most 4096 samples");
    }

    #[test]
    fn details_appear_only_when_the_brief_words_agree() {
        let soft = RenderSettings {
            soft_shadows: true,
            light_size: 0.5,
            ..base()
        };
        let softer = RenderSettings {
            light_size: 2.0,
            ..soft.clone()
        };
        assert_eq!(
            differences(&soft, &softer, [&VIEW; 2]),
            vec![Difference {
                a: "soft shadows on, light size 0.5".into(),
                b: "soft shadows on, light size 2".into(),
            }]
        );
        // N matters without AA when it stratifies soft shadows...
        let n3 = RenderSettings {
            samples: 3,
            ..soft.clone()
        };
        assert_eq!(differences(&soft, &n3, [&VIEW; 2])[0].b, "no AA, N = 3");
        // ...but not for one hard-shadowed sample per pixel.
        let hard_n3 = RenderSettings {
            samples: 3,
            ..base()
        };
        assert!(differences(&base(), &hard_n3, [&VIEW; 2]).is_empty());
        // Turning DOF on with the same N says only that.
        let dof = RenderSettings {
            depth_of_field: true,
            lens_override: LensOverride {
                aperture: Some(4.0),
                focal: None,
            },
            ..base()
        };
        assert_eq!(
            differences(&base(), &dof, [&VIEW; 2]),
            vec![Difference {
                a: "no DOF".into(),
                b: "DOF aperture 4 focal 1".into(),
            }]
        );
        // A BVH ignores the grid multiplier.
        let bvh = |m| RenderSettings {
            accel: AccelKind::Bvh,
            grid_multiplier: m,
            ..base()
        };
        assert!(differences(&bvh(1.0), &bvh(3.0), [&VIEW; 2]).is_empty());
    }

    #[test]
    fn other_settings_are_listed_too() {
        let b = RenderSettings {
            width: 64,
            height: 32,
            max_depth: 2,
            seed: 9,
            ..base()
        };
        let diffs = differences(&base(), &b, [&VIEW; 2]);
        let words: Vec<&str> = diffs.iter().map(|d| d.b.as_str()).collect();
        assert_eq!(words, ["64x32", "depth 2", "seed 9"]);
        assert_eq!(diffs[0].a, "512x512");
    }
}
