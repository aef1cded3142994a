//! Procedural scenes after Eric Haines's Standard Procedural Databases
//! (SPD): the classic ray-tracing benchmarks, recomputed here from their
//! published algorithms so the workbench ships its own scenes at any size.
//! Each generator builds a [`Scene`] document, ready for
//! [`crate::scene::write_p3f`]; the same name, level and seed always give
//! the same scene.

mod balls;
mod common;
mod gears;
mod jacks;
mod lattice;
mod mount;
mod rings;
mod shells;
pub mod sky;
mod sombrero;
mod teapot;
mod tetra;
mod tree;

use std::fmt;
use std::ops::RangeInclusive;
use std::str::FromStr;

use crate::scene::Scene;

/// The scene families the workbench can generate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum GeneratorName {
    /// The sphereflake: spheres with nine smaller children, recursively.
    Balls,
    /// A fractal mountain by midpoint displacement.
    Mount,
    /// The Sierpinski tetrahedron.
    Tetra,
    /// Interlocking rings of cylinders and spheres.
    Rings,
    /// A recursive tree of tapering cones.
    Tree,
    /// Layers of meshing spur gears.
    Gears,
    /// A seashell of spheres along a logarithmic spiral.
    Shells,
    /// A cube of balls joined by thin cylinders.
    Lattice,
    /// The children's toy: crossed cylinders with balls on their ends.
    Jacks,
    /// A damped cosine ripple as one triangle mesh.
    Sombrero,
    /// Newell's teapot, its Bezier patches tessellated.
    Teapot,
}

impl GeneratorName {
    /// Every generator, for listings and exhaustive tests.
    pub const ALL: [GeneratorName; 11] = [
        GeneratorName::Balls,
        GeneratorName::Mount,
        GeneratorName::Tetra,
        GeneratorName::Rings,
        GeneratorName::Tree,
        GeneratorName::Gears,
        GeneratorName::Shells,
        GeneratorName::Lattice,
        GeneratorName::Jacks,
        GeneratorName::Sombrero,
        GeneratorName::Teapot,
    ];

    /// The name used on the command line (`workbench gen balls`).
    pub fn name(self) -> &'static str {
        match self {
            GeneratorName::Balls => "balls",
            GeneratorName::Mount => "mount",
            GeneratorName::Tetra => "tetra",
            GeneratorName::Rings => "rings",
            GeneratorName::Tree => "tree",
            GeneratorName::Gears => "gears",
            GeneratorName::Shells => "shells",
            GeneratorName::Lattice => "lattice",
            GeneratorName::Jacks => "jacks",
            GeneratorName::Sombrero => "sombrero",
            GeneratorName::Teapot => "teapot",
        }
    }
}

impl fmt::Display for GeneratorName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for GeneratorName {
    type Err = GenerateError;

    /// Case-insensitive, so `Balls` and `balls` both work on a command line.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        GeneratorName::ALL
            .into_iter()
            .find(|g| g.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| GenerateError::UnknownGenerator(s.to_string()))
    }
}

/// What to generate: the size (meaning depends on the generator, see
/// [`level_range`]) and the seed of any randomness.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct GenerateOptions {
    /// The size; valid values depend on the generator ([`level_range`]).
    pub level: u32,
    /// Seed of the generator's randomness: equal seeds give equal scenes.
    pub seed: u64,
}

/// Why a scene could not be generated.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum GenerateError {
    #[error(
        "unknown generator `{0}` (expected one of balls, mount, tetra, rings, tree, gears, shells, lattice, jacks, sombrero, teapot)"
    )]
    /// A name that is no generator.
    UnknownGenerator(String),
    #[error("{name} level {level} is outside the valid range {}..={}", range.start(), range.end())]
    /// A level outside the generator's range.
    LevelOutOfRange {
        /// The generator.
        name: GeneratorName,
        /// The level asked for.
        level: u32,
        /// The levels it accepts.
        range: RangeInclusive<u32>,
    },
}

/// The valid levels of each generator. Counts per level:
/// - balls 0..=5: sum of 9^k spheres for k = 0..=level (1, 10, 91, 820, 7381, 66430);
/// - mount 0..=9: 2 * 4^level triangles (level 8 = 131072) plus 4 glass spheres;
/// - tetra 0..=8: 4^level tetrahedra, 4 triangles each;
/// - rings 1..=12: a pyramid of `level` layers of k x k groups of 6 rings,
///   each ring 5 cylinders and 5 spheres;
/// - tree 1..=16: `level` generations of binary branching, 2^level - 1 cones,
///   2^(level-1) - 1 joint spheres and 2^(level-1) leaves;
/// - gears 1..=8: `level` layers of level x level meshing gears, 146
///   polygons each (two 144-vertex faces, 144 wall quads);
/// - shells 1..=10: 45 * 2^level + 1 overlapping spheres on a spiral;
/// - lattice 1..=24: (level + 1)^3 balls joined by cylinders;
/// - jacks 1..=7: `level` generations of recursive jacks, 1 + 6 (5^(level-1)
///   - 1) / 4 jacks of 3 cylinders and 6 balls;
/// - sombrero 2..=10: a height field of 2 * 4^level triangles;
/// - teapot 2..=64: 64 level^2 - 8 level triangles (32 patches of
///   level x level cells) on level^2 checkerboard squares.
pub fn level_range(name: GeneratorName) -> RangeInclusive<u32> {
    match name {
        GeneratorName::Balls => balls::LEVELS,
        GeneratorName::Mount => mount::LEVELS,
        GeneratorName::Tetra => tetra::LEVELS,
        GeneratorName::Rings => rings::LEVELS,
        GeneratorName::Tree => tree::LEVELS,
        GeneratorName::Gears => gears::LEVELS,
        GeneratorName::Shells => shells::LEVELS,
        GeneratorName::Lattice => lattice::LEVELS,
        GeneratorName::Jacks => jacks::LEVELS,
        GeneratorName::Sombrero => sombrero::LEVELS,
        GeneratorName::Teapot => teapot::LEVELS,
    }
}

/// The SPD's standard size for each scene (about 10,000 primitives), the
/// size its published timings refer to.
pub fn default_level(name: GeneratorName) -> u32 {
    match name {
        GeneratorName::Balls => 4,
        GeneratorName::Mount => 6,
        GeneratorName::Tetra => 6,
        GeneratorName::Rings => 7,
        GeneratorName::Tree => 10,
        GeneratorName::Gears => 4,
        GeneratorName::Shells => 7,
        GeneratorName::Lattice => 11,
        GeneratorName::Jacks => 5,
        GeneratorName::Sombrero => 7,
        GeneratorName::Teapot => 12,
    }
}

/// Whether `name` draws anything at random, so that a seed changes it:
/// the others build the same scene whatever the seed.
pub fn uses_seed(name: GeneratorName) -> bool {
    matches!(
        name,
        GeneratorName::Mount | GeneratorName::Tree | GeneratorName::Gears
    )
}

/// Generates the scene `name` at `options.level`, with randomness drawn
/// from `options.seed` (only where [`uses_seed`]).
pub fn generate(name: GeneratorName, options: &GenerateOptions) -> Result<Scene, GenerateError> {
    let level = options.level;
    let range = level_range(name);
    if !range.contains(&level) {
        return Err(GenerateError::LevelOutOfRange { name, level, range });
    }
    let seed = options.seed;
    Ok(match name {
        GeneratorName::Balls => balls::generate(level),
        GeneratorName::Mount => mount::generate(level, seed),
        GeneratorName::Tetra => tetra::generate(level),
        GeneratorName::Rings => rings::generate(level),
        GeneratorName::Tree => tree::generate(level, seed),
        GeneratorName::Gears => gears::generate(level, seed),
        GeneratorName::Shells => shells::generate(level),
        GeneratorName::Lattice => lattice::generate(level),
        GeneratorName::Jacks => jacks::generate(level),
        GeneratorName::Sombrero => sombrero::generate(level),
        GeneratorName::Teapot => teapot::generate(level),
    })
}

/// A one-line header for a generated file (the P3F writer cannot store
/// comments, so callers prepend it as `# ...`): what the scene holds and
/// the command that regenerates it.
pub fn describe(name: GeneratorName, level: u32, seed: u64) -> String {
    let range = level_range(name);
    let what = if range.contains(&level) {
        match name {
            GeneratorName::Balls => balls::describe(level),
            GeneratorName::Mount => mount::describe(level),
            GeneratorName::Tetra => tetra::describe(level),
            GeneratorName::Rings => rings::describe(level),
            GeneratorName::Tree => tree::describe(level),
            GeneratorName::Gears => gears::describe(level),
            GeneratorName::Shells => shells::describe(level),
            GeneratorName::Lattice => lattice::describe(level),
            GeneratorName::Jacks => jacks::describe(level),
            GeneratorName::Sombrero => sombrero::describe(level),
            GeneratorName::Teapot => teapot::describe(level),
        }
    } else {
        format!("invalid level (valid: {}..={})", range.start(), range.end())
    };
    let seed_arg = if seed == 0 {
        String::new()
    } else {
        format!(" --seed {seed}")
    };
    format!(
        "{name} level {level} (seed {seed}): {what}; generated by `workbench gen {name} --level {level}{seed_arg}`"
    )
}

#[cfg(test)]
mod tests;
