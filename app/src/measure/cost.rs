//! What a frame will cost before it is rendered: brute force (`accel 0`,
//! as many course files ask) tests every ray against every primitive, and
//! over a large mesh that looks like a hang. The estimate lets the command
//! line warn and the window offer the switch to a BVH.

use tracer::accel::AccelKind;
use tracer::render::RenderSettings;
use tracer::stats::SceneCounts;

use crate::describe::si;

/// Ray-primitive tests per frame above which brute force is worth a
/// warning: at roughly 10^8 tests a second per core, several seconds to
/// many minutes on this kind of machine (a 100 000-triangle course file at
/// 512 x 512 is 5 x 10^10 and ran over 10 minutes).
pub(crate) const WARN_ABOVE_TESTS: f64 = 2e9;

/// The cost of one brute-force frame, when it is large.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BruteForceCost {
    pub(crate) primitives: usize,
    /// Estimated ray-primitive tests per frame: primitives x rays, with an
    /// eye ray and a shadow ray per light for every sample (reflections
    /// and refractions only add to it).
    pub(crate) tests: f64,
}

impl BruteForceCost {
    /// The cost of rendering with `settings`, when they ask for no
    /// acceleration structure and it exceeds [`WARN_ABOVE_TESTS`].
    pub(crate) fn of(settings: &RenderSettings, counts: &SceneCounts) -> Option<BruteForceCost> {
        if settings.accel != AccelKind::None {
            return None;
        }
        let samples = f64::from(settings.width)
            * f64::from(settings.height)
            * f64::from(settings.samples_per_pixel());
        let rays = samples * (1.0 + counts.lights as f64);
        let tests = rays * counts.primitives as f64;
        (tests > WARN_ABOVE_TESTS).then_some(BruteForceCost {
            primitives: counts.primitives,
            tests,
        })
    }

    /// The estimate in words, without the fix (which depends on where it
    /// is shown).
    pub(crate) fn describe(&self) -> String {
        format!(
            "no acceleration structure (accel 0) over {} primitives: about {} ray-primitive \
             tests per frame, which may take many minutes",
            self.primitives,
            si(self.tests)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn counts(primitives: usize, lights: usize) -> SceneCounts {
        SceneCounts {
            primitives,
            lights,
            ..SceneCounts::default()
        }
    }

    #[test]
    fn only_large_brute_force_frames_are_flagged() {
        let brute = RenderSettings {
            accel: AccelKind::None,
            width: 100,
            height: 100,
            ..RenderSettings::default()
        };
        // 10^4 eye rays x 2 (one light) = 2 x 10^4 rays; the threshold is
        // crossed between 10^5 and 10^5 + 1 primitives.
        assert_eq!(BruteForceCost::of(&brute, &counts(100_000, 1)), None);
        let cost = BruteForceCost::of(&brute, &counts(100_001, 1)).unwrap();
        assert_eq!(cost.tests, 2e4 * 100_001.0);
        assert!(
            cost.describe().contains("100001 primitives"),
            "{}",
            cost.describe()
        );
        // Anti-aliasing multiplies the rays.
        let aa = RenderSettings {
            antialiasing: true,
            samples: 2,
            ..brute.clone()
        };
        assert!(BruteForceCost::of(&aa, &counts(30_000, 1)).is_some());
        // Any structure: nothing to say.
        let bvh = RenderSettings {
            accel: AccelKind::Bvh,
            ..brute
        };
        assert_eq!(BruteForceCost::of(&bvh, &counts(10_000_000, 4)), None);
    }
}
