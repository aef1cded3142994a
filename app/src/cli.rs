//! The command line, as close to what the user typed as possible; turned
//! into tracer settings in one place ([`SettingsArgs::apply`]).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use tracer::accel::{AccelKind, StructureLayer};
use tracer::render::vocabulary::{self, Overrides, SamplingChoice};
use tracer::render::{Encoding, HeatScale, RenderSettings, View, ViewHeatmap};

use crate::measure::ab::Heatmap;
use crate::measure::study::Param;
use crate::reports::bench_table::Format;

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
    pub(crate) command: Option<Headless>,
    /// A scene file to open in the window (default: the bundled showcase).
    #[arg(long, global = false)]
    pub(crate) scene: Option<PathBuf>,
    /// Save a screenshot of the window to this PNG file once the render is
    /// done (or an error is shown), then close.
    #[arg(long, value_name = "PNG")]
    pub(crate) screenshot: Option<PathBuf>,
    /// Open the window with the observer view on (the scene from outside).
    #[arg(long)]
    pub(crate) observer: bool,
    /// Open the window on this lesson, its first step set up: a lesson file
    /// (see docs/LESSONS.md) or a bundled lesson's name (`--lesson shadows`).
    #[arg(long, value_name = "NAME|TOML", conflicts_with = "scene")]
    pub(crate) lesson: Option<PathBuf>,
    /// Add a folder of lessons (its .toml files, or those its
    /// lessons.index names) to the Lessons panel's list, by chapter after
    /// the bundled ones of the same chapter, and set up the folder's first
    /// (or the --lesson file, if given).
    #[arg(long, value_name = "DIR", conflicts_with = "scene")]
    pub(crate) lesson_folder: Option<PathBuf>,
    /// Take the screenshot this many seconds after opening instead.
    #[arg(long, value_name = "SECONDS", requires = "screenshot")]
    pub(crate) screenshot_after: Option<f64>,
}

impl Cli {
    /// The window's screenshot request, checked: a delay must be a finite,
    /// non-negative number of seconds.
    pub(crate) fn screenshot_plan(&self) -> anyhow::Result<Option<ScreenshotPlan>> {
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
        Ok(Some(ScreenshotPlan {
            path: path.clone(),
            after,
        }))
    }
}

/// When and where the window takes its screenshot (`--screenshot`).
#[derive(Debug, Clone)]
pub struct ScreenshotPlan {
    pub(crate) path: PathBuf,
    /// Take it this long after the window opened; `None`: once the render
    /// is finished and on screen (or an error is shown).
    pub(crate) after: Option<std::time::Duration>,
}

/// The subcommands: the engine run without the window.
#[derive(Subcommand, Debug)]
pub(crate) enum Headless {
    /// Render a scene to a PNG file.
    Render(RenderArgs),
    /// Show every ray one sample of one pixel spawned: what each hit, its
    /// material, its shadow rays and what it added to the pixel.
    Inspect(InspectArgs),
    /// Draw the scene seen from outside: the scene camera with its image
    /// plane, the lights, and the rays of a pixel (or a row, column or grid
    /// of pixels) flying through it, as a PNG figure or JSON segments.
    Observe(ObserveArgs),
    /// Time frames of a scene with each acceleration structure, or the
    /// course report's whole timing matrix (--matrix).
    Bench(BenchArgs),
    /// Render a scene with two settings (A and B) and compare them: times,
    /// rays, MSE, PSNR, FLIP and an A | B | difference image.
    Compare(CompareArgs),
    /// Generate a procedural scene (balls, mount, tetra, rings, tree, gears,
    /// shells, lattice, jacks, sombrero, teapot) as P3F, or the sky cube (`sky`) as
    /// six PNG faces.
    Gen(GenArgs),
    /// Sweep one parameter (grid-m, spp, depth, light-size, aperture,
    /// resolution, noise-threshold, or the level of a generated scene) and
    /// time each point for each structure: a table, and a PNG chart with --plot.
    Sweep(SweepArgs),
    /// Lessons: list and check them (every step replayed: its starting state
    /// must fail its check, its solution pass it), start a new one, explain
    /// what a step starts from, and read a student's progress.
    Lesson(LessonArgs),
    /// Write the lab report: the course's experiments on a scene (Whitted
    /// depth, sampling, the timing matrix, statistics, one pixel explained,
    /// the course's own times) as one self-contained HTML page.
    Report(ReportArgs),
}

#[derive(Args, Debug)]
#[command(after_help = "\
The page has seven sections, as the course's report: the run (scene,
camera, settings, machine), Whitted ray tracing (local shading only, hard
shadows, depth 1 and the scene's), stochastic sampling (anti-aliasing, depth of field, soft shadows
off and on, error against samples), acceleration (the course's timing table
with a BVH row for each, the grid multiplier study, tests per pixel, build
time and memory), statistics, one pixel explained, and the course's own
times beside ours for balls_medium. Each time is the median of --runs
frames on --threads threads, stated in the page.

The report varies the structure, shadows, anti-aliasing and depth of field
itself and samples uniformly, as the course did: --accel, --aa, --no-aa,
--soft-shadows, --no-shadows, --dof and the adaptive sampling flags are
refused. The other settings flags apply to every experiment (--spp sets
the timing table's N, 4 by default; --aperture and --focal its lens).

Images are inline PNG and charts inline SVG: the file opens in any browser
without a network and prints to PDF. Ctrl-C stops and writes nothing.

  workbench report scenes/balls_medium.p3f -o report.html --quick
  workbench report scene.p3f -o report.html --runs 7 --json times.json")]
pub(crate) struct ReportArgs {
    /// The scene file (.p3f or .nff).
    pub(crate) scene: PathBuf,
    /// Where to write the HTML page.
    #[arg(short, long, default_value = "report.html")]
    pub(crate) output: PathBuf,
    /// Frames per timed configuration; the median and spread are reported.
    #[arg(long, default_value_t = 5)]
    pub(crate) runs: usize,
    /// A quick report: images at most 128 pixels on their longer side and
    /// at most 3 runs per time (said in the page).
    #[arg(long)]
    pub(crate) quick: bool,
    /// The pixel to explain (default: one the report chooses, with a
    /// reflection and a blocked shadow ray), in the measured image.
    #[arg(long, num_args = 2, value_names = ["X", "Y"])]
    pub(crate) pixel: Option<Vec<u32>>,
    /// Also write the timing table as `bench --matrix --format json`
    /// writes it.
    #[arg(long, value_name = "FILE")]
    pub(crate) json: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) settings: SettingsArgs,
    #[command(flatten)]
    pub(crate) encoding: EncodingArgs,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = thread_count)]
    pub(crate) threads: Option<usize>,
}

#[derive(Args, Debug)]
pub(crate) struct LessonArgs {
    #[command(subcommand)]
    pub(crate) command: LessonCommand,
}

#[derive(Subcommand, Debug)]
pub(crate) enum LessonCommand {
    /// The bundled lessons, or a folder's: name, chapter, title and steps,
    /// in chapter order.
    List {
        /// A table, or JSON for scripts.
        #[arg(long, value_enum, default_value_t = MetricsFormat::Text)]
        format: MetricsFormat,
        /// A folder of lessons (its `.toml` files, or those its
        /// lessons.index names) instead of the bundled ones.
        #[arg(value_name = "DIR")]
        folder: Option<PathBuf>,
    },
    /// Validate lessons (the file reads, the scene loads, the settings and
    /// edits apply), then replay each step: its starting state must fail
    /// its check and its `solution` must pass it. One line per step; the
    /// exit status is non-zero on any failure.
    Check {
        /// Bundled lesson names, lesson files (.toml) or folders of
        /// lessons; default: every bundled lesson.
        #[arg(value_name = "NAME|FILE")]
        lessons: Vec<String>,
        /// One line per step, or JSON for a teacher's CI: each lesson's
        /// steps with pass or what failed, its mistakes with line and column.
        #[arg(long, value_enum, default_value_t = MetricsFormat::Text)]
        format: MetricsFormat,
    },
    /// Write a commented starting lesson, NAME.toml, that passes `lesson
    /// check` as written: edit it from there. Never overwrites a file.
    New {
        /// The lesson's name or file (`light_and_shadow` writes
        /// light_and_shadow.toml, titled "Light and shadow").
        name: String,
    },
    /// The state a step starts from (settings, compare mode, the pinned
    /// pixel and its ray tree, the check's verdict) and every quantity a
    /// check can read there with its value; with --find, the pixels where
    /// tree figures hold, to choose one to pin.
    Explain(ExplainArgs),
    /// A student's lesson progress (the steps done per lesson, when, and
    /// the answers given) from the window's saved state or an exported
    /// file, as JSON, CSV or an HTML page; with --merge, a class's files
    /// as one table.
    Progress(ProgressArgs),
}

#[derive(Args, Debug)]
#[command(after_help = "\
  workbench lesson progress                      the window's saved progress, as JSON
  workbench lesson progress ada.json --format csv
  workbench lesson progress --merge class/*.json -o class.html

A merged table has a row per file, named by its `student` (the name typed
in the Lessons panel) or else by the file's stem, and a column per lesson
with the steps done. A progress file can be edited: it is a record, not a
proof.")]
pub(crate) struct ProgressArgs {
    /// An exported progress file (.json), or the window's saved state
    /// (app.ron); default: the window's saved state in the data folder.
    #[arg(value_name = "FILE", conflicts_with = "merge")]
    pub(crate) file: Option<PathBuf>,
    /// Merge these students' exported files into one table.
    #[arg(long, num_args = 1.., value_name = "FILE")]
    pub(crate) merge: Vec<PathBuf>,
    /// The output's format; default: from -o's extension, else JSON.
    #[arg(long, value_enum)]
    pub(crate) format: Option<ProgressFormat>,
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    pub(crate) output: Option<PathBuf>,
}

/// How `lesson progress` writes.
#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub(crate) enum ProgressFormat {
    Json,
    Csv,
    Html,
}

#[derive(Args, Debug)]
#[command(after_help = "\
  workbench lesson explain refraction --step 3
  workbench lesson explain refraction --step 3 --find eye-object=2 --find tir=yes
  workbench lesson explain my_lesson.toml --step 2 --pixel 40 27

--find takes a tree figure as a check's `of` names it (the `tree ` in front
may be left out) and what it must be as a check's `is` writes it: tir=yes,
eye-object=2, rays>=6, \"blocker 0=1\". Every --find must hold. The pixels
are listed row by row, read on side A's first sample as the step starts.")]
pub(crate) struct ExplainArgs {
    /// A bundled lesson's name or a lesson file (.toml).
    #[arg(value_name = "NAME|FILE")]
    pub(crate) lesson: String,
    /// The step, counted from 1 as `lesson check` numbers them.
    #[arg(long, default_value_t = 1, value_name = "N")]
    pub(crate) step: usize,
    /// List the pixels where this tree figure holds (repeat to ask for
    /// several at once), instead of explaining the step.
    #[arg(long, value_name = "QUANTITY=VALUE")]
    pub(crate) find: Vec<String>,
    /// Explain the step with this pixel pinned instead of the step's own.
    #[arg(long, num_args = 2, value_names = ["X", "Y"], conflicts_with = "find")]
    pub(crate) pixel: Option<Vec<u32>>,
}

#[derive(Args, Debug)]
#[command(after_help = "\
VALUES is a comma-separated list of numbers and ranges; ranges include
their end when a step lands on it, and the values are sorted:
  0.25,0.5,1      those three
  1..5            1, 2, 3, 4, 5
  1..2:0.25       1, 1.25, 1.5, 1.75, 2 (add 0.25 each step)
  0.5..8:x2       0.5, 1, 2, 4, 8 (double each step)

Each point is measured as `bench` measures a row: --runs frames, the
median, min..max, build time apart from frame time, rays/s, and tests and
steps (grid cells or BVH nodes) per ray. A built structure is reused by
every point that traces against it. Frames are one sample per pixel with
hard shadows unless the options ask for more; the swept parameter turns its
own feature on (spp: anti-aliasing, light-size: soft shadows, aperture:
depth of field, noise-threshold: adaptive anti-aliasing).

  workbench sweep scene.p3f --param grid-m --values 0.25..8:x2 --plot m.png
  workbench sweep --param level --generator balls --levels 1..4 --plot scale.png
  workbench sweep scene.p3f --param spp --values 1..6 --structures bvh
  workbench sweep scene.p3f --param noise-threshold --values 0.0025..0.04:x2

The level study renders a built-in generator's scene at each level (x axis:
primitives, log-log chart, with the slope of each structure). The spp study
also gives each image's MSE, PSNR and FLIP against a reference rendered
with twice the largest N (--reference-spp), and marks the knee of error vs
time; the noise-threshold study does the same (reference: twice the
strata of its --max-spp) and gives each point's samples per pixel.
Ctrl-C stops after the frame under way and prints what was measured
(a second Ctrl-C stops at once); the exit status is then non-zero.")]
pub(crate) struct SweepArgs {
    /// The scene file (.p3f or .nff); none for --param level.
    pub(crate) scene: Option<PathBuf>,
    /// What to sweep: grid-m, spp, depth, light-size, aperture, resolution,
    /// noise-threshold or level.
    #[arg(long, value_parser = study_param)]
    pub(crate) param: Param,
    /// The values (see below; default: a range suited to the parameter).
    /// --levels is the same option.
    #[arg(long, alias = "levels", value_name = "VALUES")]
    pub(crate) values: Option<String>,
    /// For --param level: the generator (balls, mount, tetra, ...).
    #[arg(long)]
    pub(crate) generator: Option<String>,
    /// Structures to measure (default: grid for grid-m, all three for
    /// level, else the scene's or --accel's).
    #[arg(long, value_parser = accel_kind, value_delimiter = ',')]
    pub(crate) structures: Option<Vec<AccelKind>>,
    /// Frames per point; the median and min..max are reported.
    #[arg(long, default_value_t = 3)]
    pub(crate) runs: usize,
    /// How to print the table.
    #[arg(long, value_enum, default_value_t = TableFormat::Text)]
    pub(crate) format: TableFormat,
    /// Write the chart to this PNG file.
    #[arg(long, value_name = "PNG")]
    pub(crate) plot: Option<PathBuf>,
    /// For --param spp and noise-threshold: N of the reference image
    /// (default: twice the largest N).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub(crate) reference_spp: Option<u32>,
    #[command(flatten)]
    pub(crate) settings: SettingsArgs,
    #[command(flatten)]
    pub(crate) encoding: EncodingArgs,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = thread_count)]
    pub(crate) threads: Option<usize>,
}

/// `--param NAME`, one of the study parameters.
fn study_param(text: &str) -> Result<Param, String> {
    text.parse()
}

#[derive(Args, Debug)]
pub(crate) struct GenArgs {
    /// balls, mount, tetra, rings, tree, gears, shells, lattice, jacks,
    /// sombrero, teapot or sky.
    pub(crate) name: String,
    /// Size of the scene (its meaning depends on the generator: for balls,
    /// level 2 is 91 spheres).
    #[arg(long)]
    pub(crate) level: Option<u32>,
    /// Seed of the generator's randomness (default 0).
    #[arg(long)]
    pub(crate) seed: Option<u64>,
    /// Output file (default: standard output); a folder for `sky`.
    #[arg(short, long)]
    pub(crate) output: Option<PathBuf>,
    /// Side of each sky face in pixels (default 512), for `sky`.
    #[arg(long)]
    pub(crate) size: Option<u32>,
}

#[derive(Args, Debug)]
#[command(after_help = "\
By default one row per structure, one sample per pixel and hard shadows
unless the options ask for more: build time, memory, frame time, rays/s and
work per ray.

--matrix reproduces the course report's timing table (Figure 5.1): for each
structure, hard and soft shadows, each with one sample, anti-aliasing (N x N
with the report's N = 4, or --spp N) and anti-aliasing with depth of field
(the scene's aperture, or 8 pixels when it has none): 18 rows for none, grid
and bvh. Other options (size, light size, focal, ...) apply to every row.")]
pub(crate) struct BenchArgs {
    /// The scene file (.p3f or .nff).
    pub(crate) scene: PathBuf,
    /// Frames rendered per row; the median, min..max and median absolute
    /// deviation are reported.
    #[arg(long, default_value_t = 5)]
    pub(crate) runs: usize,
    /// Structures to measure (default: --accel's, or none, grid and bvh;
    /// with --rays one, default bvh). --structure is the same option.
    #[arg(long, alias = "structure", value_parser = accel_kind, value_delimiter = ',')]
    pub(crate) structures: Option<Vec<AccelKind>>,
    /// Time the structure alone on the ray set Embree is measured on: eye
    /// rays through each pixel centre in 16 x 16 tiles (closest hit), then
    /// shadow rays from their hits to each light the surface faces (any
    /// hit), each kind on its own, --runs casts after a warm-up (text or
    /// json).
    #[arg(long, conflicts_with_all = ["matrix", "images"])]
    pub(crate) rays: bool,
    /// Measure the course report's matrix: structure x soft shadows x {one sample,
    /// AA, AA with depth of field}.
    #[arg(long)]
    pub(crate) matrix: bool,
    /// Measure the time to a given error: render a uniform reference
    /// (--reference-spp), take uniform N x N's error (--spp, default 4) or
    /// --target-mse as the target, find the cheapest uniform N and the
    /// largest adaptive --noise-threshold that reach it (MSE and FLIP),
    /// then time both --runs times, alternated.
    #[arg(long, conflicts_with_all = ["matrix", "rays", "images"])]
    pub(crate) to_error: bool,
    /// With --to-error: N of the uniform reference (default 4 N, at most
    /// 64).
    #[arg(long, value_name = "N", requires = "to_error", value_parser = clap::value_parser!(u32).range(1..))]
    pub(crate) reference_spp: Option<u32>,
    /// With --to-error: the MSE to reach (8-bit units) instead of uniform
    /// N x N's error.
    #[arg(long, value_name = "MSE", requires = "to_error")]
    pub(crate) target_mse: Option<f64>,
    /// How to print the table.
    #[arg(long, value_enum, default_value_t = TableFormat::Text)]
    pub(crate) format: TableFormat,
    /// Write each row's image into this folder (e.g. grid_soft_aa4_dof.png).
    #[arg(long, value_name = "DIR")]
    pub(crate) images: Option<PathBuf>,
    /// Scale the --images down so their longer side is at most PX pixels.
    #[arg(long, value_name = "PX", value_parser = clap::value_parser!(u32).range(1..))]
    pub(crate) thumbnail: Option<u32>,
    #[command(flatten)]
    pub(crate) settings: SettingsArgs,
    #[command(flatten)]
    pub(crate) encoding: EncodingArgs,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = thread_count)]
    pub(crate) threads: Option<usize>,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub(crate) enum TableFormat {
    /// Aligned columns.
    Text,
    /// A Markdown table.
    Md,
    /// Comma-separated values with plain numbers.
    Csv,
    /// Every measurement as JSON.
    Json,
}

impl From<TableFormat> for Format {
    fn from(f: TableFormat) -> Self {
        match f {
            TableFormat::Text => Format::Text,
            TableFormat::Md => Format::Markdown,
            TableFormat::Csv => Format::Csv,
            TableFormat::Json => Format::Json,
        }
    }
}

#[derive(Args, Debug)]
#[command(after_help = "\
Each side starts from the scene's settings, then the options given to
compare itself (for both sides), then its own --a / --b flags, e.g.

  workbench compare scene.p3f --width 256 --height 256 \\
      --a \"--accel none\" --b \"--accel grid --grid-m 4 --aa --spp 4\"

The image is A | B | difference, with a legend bar under the difference
(0 on the left, the largest value on the right).

--b-image compares side A with an image instead of a second render (another
renderer's output, an earlier figure): PNG, JPEG or OpenEXR (linear, encoded
as A is), of A's size, or resized to it with --fit:

  workbench compare scene.p3f --a \"--aa --spp 4\" --b-image ref.png -o out.png


With --view VIEW the image is A's view | B's view | |A - B| of the view's
values, A and B on one shared scale, so both read against one legend. Each
side renders once more to measure its view: the times stay those of the
plain render.")]
pub(crate) struct CompareArgs {
    /// The scene file (.p3f or .nff).
    pub(crate) scene: PathBuf,
    /// Side A: flags of `workbench render` in one string (e.g. "--aa --spp 4").
    #[arg(
        long,
        value_name = "FLAGS",
        default_value = "",
        allow_hyphen_values = true
    )]
    pub(crate) a: String,
    /// Side B: flags of `workbench render` in one string.
    #[arg(
        long,
        value_name = "FLAGS",
        default_value = "",
        allow_hyphen_values = true,
        conflicts_with = "b_image"
    )]
    pub(crate) b: String,
    /// Side B is this image (PNG, JPEG or EXR) instead of a second render.
    #[arg(long, value_name = "IMAGE")]
    pub(crate) b_image: Option<PathBuf>,
    /// B, adaptive, at A's cost: it stops when its samples reach the total
    /// A's render took (`samples`), or once it has rendered as long as A
    /// did (`time`, which depends on the machine). A renders first.
    #[arg(long, value_enum, value_name = "COST", conflicts_with = "b_image")]
    pub(crate) b_matches: Option<crate::measure::ab::Match>,
    /// Resize the --b-image to the render's size instead of refusing a
    /// mismatch.
    #[arg(long, requires = "b_image")]
    pub(crate) fit: bool,
    /// Where to write the A | B | difference PNG.
    #[arg(short, long, default_value = "compare.png")]
    pub(crate) output: PathBuf,
    /// What the difference panel shows.
    #[arg(long, value_enum, default_value_t = HeatmapArg::Flip)]
    pub(crate) heatmap: HeatmapArg,
    /// How to print the times and metrics.
    #[arg(long, value_enum, default_value_t = MetricsFormat::Text)]
    pub(crate) format: MetricsFormat,
    // With --view: A's view | B's view | their difference, on one scale.
    #[command(flatten)]
    pub(crate) view: ViewArgs,
    #[command(flatten)]
    pub(crate) settings: SettingsArgs,
    #[command(flatten)]
    pub(crate) encoding: EncodingArgs,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = thread_count)]
    pub(crate) threads: Option<usize>,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub(crate) enum HeatmapArg {
    /// FLIP's perceptual error map.
    Flip,
    /// The largest channel difference, amplified 8 times.
    Abs,
}

impl From<HeatmapArg> for Heatmap {
    fn from(h: HeatmapArg) -> Self {
        match h {
            HeatmapArg::Flip => Heatmap::Flip,
            HeatmapArg::Abs => Heatmap::Absolute,
        }
    }
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub(crate) enum MetricsFormat {
    Text,
    Json,
}

#[derive(Args, Debug)]
pub(crate) struct RenderArgs {
    /// The scene file (.p3f or .nff).
    pub(crate) scene: PathBuf,
    /// Where to write the PNG.
    #[arg(short, long, default_value = "out.png")]
    pub(crate) output: PathBuf,
    #[command(flatten)]
    pub(crate) settings: SettingsArgs,
    #[command(flatten)]
    pub(crate) encoding: EncodingArgs,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = thread_count)]
    pub(crate) threads: Option<usize>,
    /// Write the image after each pass into this folder, to see convergence.
    #[arg(long, value_name = "DIR")]
    pub(crate) progressive_out: Option<PathBuf>,
    /// Print the statistics in this format instead of the summary.
    #[arg(long, value_name = "FORMAT")]
    pub(crate) stats: Option<StatsFormat>,
    /// Write the scene, after its --set edits, to this P3F file.
    #[arg(long, value_name = "P3F")]
    pub(crate) save_scene: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) view: ViewArgs,
    /// Draw the acceleration structure over the image: bvh:DEPTH (the
    /// BVH's boxes at that depth), bvh:leaves, or grid (the grid's box and
    /// cell lattice), projected through the camera.
    #[arg(long, value_parser = parse_overlay, value_name = "bvh:DEPTH|bvh:leaves|grid")]
    pub(crate) overlay: Option<StructureLayer>,
    /// With --overlay: highlight the grid cells (or BVH nodes and leaves)
    /// this pixel's eye ray visited, from yellow (first) to red (last).
    #[arg(long, num_args = 2, value_names = ["X", "Y"], requires = "overlay")]
    pub(crate) pixel: Option<Vec<u32>>,
    /// Which of the --pixel's samples (the pass that traces it, from 0).
    #[arg(long, default_value_t = 0, value_name = "K", requires = "pixel")]
    pub(crate) sample: u32,
}

/// `--accel NAME` and each of `--structures A,B`.
fn accel_kind(text: &str) -> Result<AccelKind, String> {
    text.parse()
        .map_err(|e: tracer::accel::UnknownAccel| e.to_string())
}

fn parse_overlay(text: &str) -> Result<StructureLayer, String> {
    match text.split_once(':') {
        None if text == "grid" => Ok(StructureLayer::Grid),
        Some(("bvh", "leaves")) => Ok(StructureLayer::BvhLeaves),
        Some(("bvh", depth)) => depth
            .parse()
            .map(StructureLayer::BvhDepth)
            .map_err(|_| format!("'{depth}' is not a depth (0 is the root) or 'leaves'")),
        _ => Err(format!("'{text}' is not bvh:DEPTH, bvh:leaves or grid")),
    }
}

/// A per-pixel view instead of the shaded image, and its heat map's scale.
#[derive(Args, Debug, Clone, Default)]
pub(crate) struct ViewArgs {
    /// Write this view instead of the shaded image: tests, steps, rays,
    /// shadow, blocked, depth, distance (heat maps with a legend), normals
    /// or objects (colours).
    #[arg(long, value_parser = parse_view, value_name = "VIEW")]
    pub(crate) view: Option<View>,
    /// Top of the heat map: max, p99 (the 99th percentile) or a number.
    #[arg(long, value_parser = parse_heat_scale, value_name = "max|p99|VALUE", requires = "view")]
    pub(crate) view_scale: Option<HeatScale>,
    /// Heat map on log(1 + value).
    #[arg(long, requires = "view")]
    pub(crate) log: bool,
}

impl ViewArgs {
    /// The view asked for, unless it is the shaded image.
    pub(crate) fn view(&self) -> Option<View> {
        self.view.filter(|&v| v != View::Shaded)
    }

    /// The heat map fitting `sides` together (one shared scale).
    pub(crate) fn heatmap(&self, sides: &[&[Option<f32>]]) -> ViewHeatmap {
        ViewHeatmap::fit(self.view_scale.unwrap_or_default(), self.log, sides)
    }
}

fn parse_view(text: &str) -> Result<View, String> {
    View::from_name(text).ok_or_else(|| {
        let names: Vec<&str> = View::ALL.iter().map(|v| v.name()).collect();
        format!("no view '{text}'; views: {}", names.join(", "))
    })
}

fn parse_heat_scale(text: &str) -> Result<HeatScale, String> {
    match text {
        "max" => Ok(HeatScale::Max),
        "p99" => Ok(HeatScale::P99),
        _ => match text.parse::<f32>() {
            Ok(v) if v.is_finite() && v > 0.0 => Ok(HeatScale::Fixed(v)),
            _ => Err(format!("'{text}' is not max, p99 or a positive number")),
        },
    }
}

#[derive(Args, Debug)]
#[command(after_help = "\
The figure is the scene rendered from an observer camera (by default
behind, above and to the side of the scene camera, framing the scene and
the lights near it), with the scene camera's frustum, its image plane
showing the render, the lens and the plane in focus with depth of field,
the lights (and their areas with soft shadows), and every ray of the
pixel's sample: eye white, reflection blue, refraction pink, shadow rays
yellow (dashed and ending at the occluder when blocked), a green tick
along each hit's normal.
What a surface hides is drawn faint.

  workbench observe scene.p3f --pixel 160 150 -o figure.png
  workbench observe scene.p3f --pixel 160 150 --pixels row:150 --format json")]
pub(crate) struct ObserveArgs {
    /// The scene file (.p3f or .nff).
    pub(crate) scene: PathBuf,
    /// The pixel whose rays are drawn, from the top-left corner.
    #[arg(long, num_args = 2, value_names = ["X", "Y"], required = true)]
    pub(crate) pixel: Vec<u32>,
    /// Also draw these pixels' rays: row:Y, column:X (32 pixels along it)
    /// or grid:STEP (one pixel every STEP).
    #[arg(long, value_parser = pixel_pattern, value_name = "row:Y|column:X|grid:STEP")]
    pub(crate) pixels: Option<crate::figures::observer::PixelPattern>,
    /// Which of the pixels' samples (the pass that traces it, from 0).
    #[arg(long, default_value_t = 0, value_name = "K")]
    pub(crate) sample: u32,
    /// Where the observer stands (default: framed on the scene).
    #[arg(long, num_args = 3, value_names = ["X", "Y", "Z"], requires = "at", allow_negative_numbers = true)]
    pub(crate) from: Option<Vec<f32>>,
    /// What the observer looks at.
    #[arg(long, num_args = 3, value_names = ["X", "Y", "Z"], requires = "from", allow_negative_numbers = true)]
    pub(crate) at: Option<Vec<f32>>,
    /// The observer's up (default: the scene camera's).
    #[arg(long, num_args = 3, value_names = ["X", "Y", "Z"], allow_negative_numbers = true)]
    pub(crate) up: Option<Vec<f32>>,
    /// The figure's size in pixels.
    #[arg(long, num_args = 2, value_names = ["W", "H"], default_values_t = [800, 600])]
    pub(crate) size: Vec<u32>,
    /// Draw the acceleration structure too: bvh:DEPTH, bvh:leaves or grid,
    /// with the pixel's eye-ray walk through it.
    #[arg(long, value_parser = parse_overlay, value_name = "bvh:DEPTH|bvh:leaves|grid")]
    pub(crate) overlay: Option<StructureLayer>,
    /// Where to write the figure.
    #[arg(short, long, default_value = "observe.png")]
    pub(crate) output: PathBuf,
    /// A summary, or every drawn segment as JSON.
    #[arg(long, value_enum, default_value_t = MetricsFormat::Text)]
    pub(crate) format: MetricsFormat,
    #[command(flatten)]
    pub(crate) settings: SettingsArgs,
    #[command(flatten)]
    pub(crate) encoding: EncodingArgs,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = thread_count)]
    pub(crate) threads: Option<usize>,
}

fn pixel_pattern(text: &str) -> Result<crate::figures::observer::PixelPattern, String> {
    text.parse()
}

#[derive(Args, Debug)]
pub(crate) struct InspectArgs {
    /// The scene file (.p3f or .nff).
    pub(crate) scene: PathBuf,
    /// The pixel, from the top-left corner.
    #[arg(long, num_args = 2, value_names = ["X", "Y"], required = true)]
    pub(crate) pixel: Vec<u32>,
    /// Which of the pixel's samples (the pass that traces it, from 0).
    #[arg(long, default_value_t = 0, value_name = "K")]
    pub(crate) sample: u32,
    #[command(flatten)]
    pub(crate) settings: SettingsArgs,
    /// An indented tree to read, or JSON for scripts.
    #[arg(long, value_enum, default_value_t = MetricsFormat::Text)]
    pub(crate) format: MetricsFormat,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub(crate) enum StatsFormat {
    Json,
}

/// `--sampling`: how anti-aliasing spends its samples.
#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub(crate) enum SamplingMode {
    /// N x N jittered samples in every pixel.
    Uniform,
    /// Samples where each pixel's estimated error asks for them.
    Adaptive,
}

/// Overrides of the scene's own settings; anything left out keeps the
/// scene's value (or the tracer's default).
#[derive(Args, Debug, Default, Clone)]
pub struct SettingsArgs {
    /// Image width in pixels.
    #[arg(long)]
    pub(crate) width: Option<u32>,
    /// Image height in pixels.
    #[arg(long)]
    pub(crate) height: Option<u32>,
    /// Maximum number of bounces (default 4).
    #[arg(long)]
    pub(crate) depth: Option<u32>,
    /// Anti-aliasing on (jittered N x N samples per pixel).
    #[arg(long, overrides_with = "no_aa")]
    pub(crate) aa: bool,
    /// Anti-aliasing off (one sample at the pixel centre).
    #[arg(long, overrides_with = "aa")]
    pub(crate) no_aa: bool,
    /// N: N x N samples per pixel (and lens / soft-shadow strata).
    #[arg(long, value_name = "N")]
    pub(crate) spp: Option<u32>,
    /// How anti-aliasing spends its samples: uniform (N x N in every
    /// pixel) or adaptive (until each pixel's estimated error is below
    /// --noise-threshold; turns anti-aliasing on).
    #[arg(long, value_enum, value_name = "MODE")]
    pub(crate) sampling: Option<SamplingMode>,
    /// Adaptive sampling: a pixel stops once its error estimate (its last
    /// pass's mean against the mean before it) is below T, in display
    /// units 0..1 (default 0.01, 2.55 levels of 255; 0 takes --max-spp
    /// everywhere). Implies --sampling adaptive.
    #[arg(long, value_name = "T")]
    pub(crate) noise_threshold: Option<f32>,
    /// Adaptive sampling: samples every pixel takes first (default N^2/4,
    /// at least 4). Implies --sampling adaptive.
    #[arg(long, value_name = "M")]
    pub(crate) min_spp: Option<u32>,
    /// Adaptive sampling: samples no pixel exceeds (default (2N)^2).
    /// Implies --sampling adaptive.
    #[arg(long, value_name = "X")]
    pub(crate) max_spp: Option<u32>,
    /// Soft shadows: lights get an area.
    #[arg(long)]
    pub(crate) soft_shadows: bool,
    /// Shadows off: no shadow rays, every light reaches every point that
    /// faces it (local shading only).
    #[arg(long)]
    pub(crate) no_shadows: bool,
    /// Side of the square a point light becomes with soft shadows (scene units).
    #[arg(long, value_name = "SIZE")]
    pub(crate) light_size: Option<f32>,
    /// Depth of field with the scene's (or the given) aperture and focal ratio.
    #[arg(long)]
    pub(crate) dof: bool,
    /// Lens diameter in pixels (implies --dof when > 0).
    #[arg(long)]
    pub(crate) aperture: Option<f32>,
    /// Focal distance as a multiple of the view-plane distance.
    #[arg(long)]
    pub(crate) focal: Option<f32>,
    /// Ambient light intensity (default 0.1).
    #[arg(long)]
    pub(crate) ambient: Option<f32>,
    /// Acceleration structure: none, grid (the course's uniform grid) or
    /// bvh.
    #[arg(long, value_parser = accel_kind)]
    pub(crate) accel: Option<AccelKind>,
    /// Uniform grid cell multiplier m.
    #[arg(long, value_name = "M")]
    pub(crate) grid_m: Option<f32>,
    /// Seed of the random numbers.
    #[arg(long)]
    pub(crate) seed: Option<u64>,
    /// Edit the scene before it is prepared, e.g. 'object 5 ior 1.33',
    /// 'material 2 kd 0.5', 'light 0 position 1 2 3', 'camera aperture 8';
    /// repeatable, applied in order. Objects count from 0 in the file's
    /// order, as `inspect` numbers them.
    #[arg(long = "set", value_name = "EDIT")]
    pub(crate) set: Vec<String>,
}

/// How images are written: what the commands that write images take
/// beside the settings (`inspect` writes none).
#[derive(Args, Debug, Default, Clone)]
pub struct EncodingArgs {
    /// Encode the output with the sRGB curve instead of writing linear values.
    #[arg(long)]
    pub(crate) srgb: bool,
}

impl EncodingArgs {
    pub(crate) fn encoding(&self) -> Encoding {
        if self.srgb {
            Encoding::Srgb
        } else {
            Encoding::Linear
        }
    }
}

/// The settings flags alone, to read `compare --a "..."` strings with the
/// same definition as `render`.
#[derive(Parser, Debug)]
#[command(no_binary_name = true, disable_help_flag = true)]
struct SettingsLine {
    #[command(flatten)]
    settings: SettingsArgs,
    #[command(flatten)]
    encoding: EncodingArgs,
}

impl SettingsArgs {
    /// Reads settings flags (and `--srgb`) from one string, as `workbench
    /// render` takes them ("--accel grid --grid-m 4 --aa"). Whitespace
    /// separates the words, except inside quotes (`--set 'object 5 ior
    /// 1.33'`). The error names the bad flag or value, e.g. "unexpected
    /// argument '--fast' found".
    pub(crate) fn parse_str(text: &str) -> Result<(SettingsArgs, EncodingArgs), String> {
        Self::parse_words(vocabulary::split_words(text).map_err(|e| e.to_string())?)
    }

    /// [`SettingsArgs::parse_str`] of words already split.
    fn parse_words(
        words: impl IntoIterator<Item = String>,
    ) -> Result<(SettingsArgs, EncodingArgs), String> {
        SettingsLine::try_parse_from(words)
            .map(|line| (line.settings, line.encoding))
            .map_err(|e| {
                let message = e.render().to_string();
                let first = message.lines().next().unwrap_or_default();
                first.strip_prefix("error: ").unwrap_or(first).to_string()
            })
    }

    /// Applies the overrides to settings taken from the scene.
    pub(crate) fn apply(&self, s: &mut RenderSettings) {
        self.overrides().apply(s);
    }

    /// The flags in the settings' own vocabulary, which lessons read
    /// without this parser: the command line is one front end to it.
    pub(crate) fn overrides(&self) -> Overrides {
        Overrides {
            width: self.width,
            height: self.height,
            depth: self.depth,
            aa: self.aa,
            spp: self.spp,
            sampling: self.sampling.map(|mode| match mode {
                SamplingMode::Uniform => SamplingChoice::Uniform,
                SamplingMode::Adaptive => SamplingChoice::Adaptive,
            }),
            noise_threshold: self.noise_threshold,
            min_spp: self.min_spp,
            max_spp: self.max_spp,
            no_aa: self.no_aa,
            soft_shadows: self.soft_shadows,
            no_shadows: self.no_shadows,
            light_size: self.light_size,
            aperture: self.aperture,
            dof: self.dof,
            focal: self.focal,
            ambient: self.ambient,
            accel: self.accel,
            grid_m: self.grid_m,
            seed: self.seed,
        }
    }
}

/// Most worker threads accepted: starting and stopping threads costs more
/// than they render beyond this (20 000 threads took over a minute for an
/// 8 x 8 image).
pub(crate) const MAX_THREADS: usize = 1024;

/// `--threads N` with N in 0..=[`MAX_THREADS`] (0: every core).
fn thread_count(text: &str) -> Result<usize, String> {
    let n: usize = text.parse().map_err(|e| format!("{e}"))?;
    if n > MAX_THREADS {
        return Err(format!("at most {MAX_THREADS} threads, found {n}"));
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_parse_from_a_string() {
        let (args, encoding) =
            SettingsArgs::parse_str("--accel grid  --grid-m 4 --aa --spp 4 --srgb").unwrap();
        assert_eq!(encoding.encoding(), Encoding::Srgb);
        let mut s = RenderSettings::default();
        args.apply(&mut s);
        assert_eq!(s.accel, AccelKind::Grid);
        assert_eq!(
            (s.grid_multiplier, s.antialiasing, s.samples),
            (4.0, true, 4)
        );
        assert!(SettingsArgs::parse_str("").is_ok());
        assert!(SettingsArgs::parse_str("  ").is_ok());
    }

    #[test]
    fn settings_strings_keep_quoted_edits_whole() {
        let (args, _) =
            SettingsArgs::parse_str("--aa --set 'object 5 ior 1.33' --set \"camera focal 2\"")
                .unwrap();
        assert_eq!(args.set, ["object 5 ior 1.33", "camera focal 2"]);
        assert!(args.aa);
        let open = SettingsArgs::parse_str("--set 'object 5").unwrap_err();
        assert!(open.contains("quote is not closed"), "{open}");
    }

    /// The command line is one front end to the settings' vocabulary:
    /// each word, given as a flag, means what the vocabulary reads it as
    /// (a flag renamed here fails this test, and no lesson).
    #[test]
    fn every_setting_word_is_a_flag_that_means_the_same() {
        use tracer::render::vocabulary::{Takes, WORDS};
        for word in WORDS {
            let mut line = vec![format!("--{}", word.name)];
            match word.takes {
                Takes::Nothing => {}
                Takes::Whole => line.push("3".into()),
                Takes::Number => line.push("0.25".into()),
                Takes::OneOf(names) => line.push(names[names.len() - 1].into()),
            }
            let (flags, _) = SettingsArgs::parse_words(line.clone()).unwrap();
            let words = Overrides::parse(&line).unwrap();
            assert_eq!(flags.overrides(), words, "{line:?}");
        }
    }

    #[test]
    fn a_bad_settings_string_names_the_flag() {
        let unknown = SettingsArgs::parse_str("--aa --fast").unwrap_err();
        assert!(unknown.contains("'--fast'"), "{unknown}");
        let value = SettingsArgs::parse_str("--spp many").unwrap_err();
        assert!(value.contains("--spp") && value.contains("many"), "{value}");
        let choice = SettingsArgs::parse_str("--accel octree").unwrap_err();
        assert!(
            choice.contains("--accel") && choice.contains("octree"),
            "{choice}"
        );
        let positional = SettingsArgs::parse_str("scene.p3f").unwrap_err();
        assert!(positional.contains("scene.p3f"), "{positional}");
        // Not `render`'s own flags: the threads and output belong to compare.
        assert!(SettingsArgs::parse_str("--threads 2").is_err());
    }
}
