//! The command line, as close to what the user typed as possible; turned
//! into tracer settings in one place ([`SettingsArgs::apply`]).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use tracer::accel::AccelKind;
use tracer::render::{Encoding, RenderSettings};

#[derive(Parser, Debug)]
#[command(
    name = "workbench",
    version,
    about = "Whitted Workbench: explore a classic CPU ray tracer",
    long_about = "Whitted Workbench: explore a classic CPU ray tracer.\n\n\
                  Without a subcommand it opens the window; subcommands run the\n\
                  renderer headless on NFF/P3F scene files."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// A scene file to open in the window (default: the bundled showcase).
    #[arg(long, global = false)]
    pub scene: Option<PathBuf>,
    /// Save a screenshot of the window to this PNG file once the render is
    /// done (or an error is shown), then close.
    #[arg(long, value_name = "PNG")]
    pub screenshot: Option<PathBuf>,
    /// Take the screenshot this many seconds after opening instead.
    #[arg(long, value_name = "SECONDS", requires = "screenshot")]
    pub screenshot_after: Option<f64>,
}

impl Cli {
    /// The window's screenshot request, checked: a delay must be a finite,
    /// non-negative number of seconds.
    pub fn screenshot_plan(&self) -> anyhow::Result<Option<crate::gui::ScreenshotPlan>> {
        let Some(path) = &self.screenshot else {
            return Ok(None);
        };
        let after =
            match self.screenshot_after {
                None => None,
                Some(s) => Some(std::time::Duration::try_from_secs_f64(s).map_err(|_| {
                    anyhow::anyhow!("--screenshot-after {s}: not a delay in seconds")
                })?),
            };
        Ok(Some(crate::gui::ScreenshotPlan {
            path: path.clone(),
            after,
        }))
    }
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render a scene to a PNG file.
    Render(RenderArgs),
    /// Time frames of a scene with each acceleration structure.
    Bench(BenchArgs),
    /// Generate a procedural scene (balls, mount, tetra, rings, tree, gears)
    /// as P3F, or the sky cube (`sky`) as six PNG faces.
    Gen(GenArgs),
}

#[derive(Args, Debug)]
pub struct GenArgs {
    /// balls, mount, tetra, rings, tree, gears or sky.
    pub name: String,
    /// Size of the scene (its meaning depends on the generator: for balls,
    /// level 2 is 91 spheres).
    #[arg(long)]
    pub level: Option<u32>,
    /// Seed of the generator's randomness.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Output file (default: standard output); a folder for `sky`.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Side of each sky face in pixels.
    #[arg(long, default_value_t = 512)]
    pub size: u32,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// The scene file (.p3f or .nff).
    pub scene: PathBuf,
    /// Frames rendered per structure; the median is reported.
    #[arg(long, default_value_t = 5)]
    pub runs: usize,
    /// Structures to measure (default: none, grid, bvh).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub structures: Option<Vec<AccelArg>>,
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = thread_count)]
    pub threads: Option<usize>,
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// The scene file (.p3f or .nff).
    pub scene: PathBuf,
    /// Where to write the PNG.
    #[arg(short, long, default_value = "out.png")]
    pub output: PathBuf,
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = thread_count)]
    pub threads: Option<usize>,
    /// Write the image after each pass into this folder, to see convergence.
    #[arg(long, value_name = "DIR")]
    pub progressive_out: Option<PathBuf>,
    /// Print the statistics in this format instead of the summary.
    #[arg(long, value_name = "FORMAT")]
    pub stats: Option<StatsFormat>,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum StatsFormat {
    Json,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum AccelArg {
    None,
    Grid,
    Bvh,
}

impl From<AccelArg> for AccelKind {
    fn from(a: AccelArg) -> Self {
        match a {
            AccelArg::None => AccelKind::None,
            AccelArg::Grid => AccelKind::Grid,
            AccelArg::Bvh => AccelKind::Bvh,
        }
    }
}

/// Overrides of the scene's own settings; anything left out keeps the
/// scene's value (or the tracer's default).
#[derive(Args, Debug, Default, Clone)]
pub struct SettingsArgs {
    /// Image width in pixels.
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels.
    #[arg(long)]
    pub height: Option<u32>,
    /// Maximum number of bounces (default 4).
    #[arg(long)]
    pub depth: Option<u32>,
    /// Anti-aliasing on (jittered N x N samples per pixel).
    #[arg(long, overrides_with = "no_aa")]
    pub aa: bool,
    /// Anti-aliasing off (one sample at the pixel centre).
    #[arg(long, overrides_with = "aa")]
    pub no_aa: bool,
    /// N: N x N samples per pixel (and lens / soft-shadow strata).
    #[arg(long, value_name = "N")]
    pub spp: Option<u32>,
    /// Soft shadows: lights get an area.
    #[arg(long)]
    pub soft_shadows: bool,
    /// Side of the square a point light becomes with soft shadows (scene units).
    #[arg(long, value_name = "SIZE")]
    pub light_size: Option<f32>,
    /// Depth of field with the scene's (or the given) aperture and focal ratio.
    #[arg(long)]
    pub dof: bool,
    /// Lens diameter in pixels (implies --dof when > 0).
    #[arg(long)]
    pub aperture: Option<f32>,
    /// Focal distance as a multiple of the view-plane distance.
    #[arg(long)]
    pub focal: Option<f32>,
    /// Ambient light intensity (default 0.1).
    #[arg(long)]
    pub ambient: Option<f32>,
    /// Acceleration structure.
    #[arg(long, value_enum)]
    pub accel: Option<AccelArg>,
    /// Uniform grid cell multiplier m.
    #[arg(long, value_name = "M")]
    pub grid_m: Option<f32>,
    /// Seed of the random numbers.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Encode the output with the sRGB curve instead of writing linear values.
    #[arg(long)]
    pub srgb: bool,
}

impl SettingsArgs {
    /// Applies the overrides to settings taken from the scene.
    pub fn apply(&self, s: &mut RenderSettings) {
        if let Some(w) = self.width {
            s.width = w;
        }
        if let Some(h) = self.height {
            s.height = h;
        }
        if let Some(d) = self.depth {
            s.max_depth = d;
        }
        if self.aa {
            s.antialiasing = true;
        }
        if self.no_aa {
            s.antialiasing = false;
        }
        if let Some(n) = self.spp {
            s.samples = n.max(1);
        }
        if self.soft_shadows {
            s.soft_shadows = true;
        }
        if let Some(size) = self.light_size {
            s.light_size = size;
        }
        if let Some(a) = self.aperture {
            s.aperture = a;
            s.depth_of_field = a > 0.0;
        }
        if self.dof {
            s.depth_of_field = true;
        }
        if let Some(f) = self.focal {
            s.focal = f;
        }
        if let Some(a) = self.ambient {
            s.ambient = a;
        }
        if let Some(a) = self.accel {
            s.accel = a.into();
        }
        if let Some(m) = self.grid_m {
            s.grid_multiplier = m;
        }
        if let Some(seed) = self.seed {
            s.seed = seed;
        }
    }

    pub fn encoding(&self) -> Encoding {
        if self.srgb {
            Encoding::Srgb
        } else {
            Encoding::Linear
        }
    }
}

/// Most worker threads accepted: starting and stopping threads costs more
/// than they render beyond this (20 000 threads took over a minute for an
/// 8 x 8 image).
pub const MAX_THREADS: usize = 1024;

/// `--threads N` with N in 0..=[`MAX_THREADS`] (0: every core).
fn thread_count(text: &str) -> Result<usize, String> {
    let n: usize = text.parse().map_err(|e| format!("{e}"))?;
    if n > MAX_THREADS {
        return Err(format!("at most {MAX_THREADS} threads, found {n}"));
    }
    Ok(n)
}
