//! Serialises a scene document back to P3F.

use super::Scene;

/// The scene as P3F text that parses back to an equal [`Scene`].
pub fn write_p3f(scene: &Scene) -> String {
    todo!("{scene:?}")
}
