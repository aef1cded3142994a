//! What a web page can do instead of opening the window, asked for by its
//! query: `?replay` walks every bundled lesson's steps in the browser, as
//! `workbench lesson check` does on the desktop, for a script (and a
//! teacher) to see that each step passes with the web's maths library;
//! `?bench=SCENE` times `workbench bench`'s frame of a scene on the
//! page's workers, for the web's speed against the desktop's;
//! `?compare=SCENE&a=FLAGS&b=FLAGS` measures what `workbench compare`
//! does (MSE, PSNR, FLIP), for the web's metrics against the desktop's;
//! `?study=SCENE&param=P&values=V` runs a study on a worker and gives its
//! chart as a download, for a script to see that charts draw on the web.

use std::sync::atomic::AtomicBool;
use std::sync::mpsc;

use anyhow::Context;
use tracer::accel::AccelKind;
use tracer::render::{Encoding, RenderSettings};
use wasm_bindgen::prelude::*;

use crate::cli::{EncodingArgs, SettingsArgs};
use crate::compare_side::side_from_flags;
use crate::figures::study_plot;
use crate::gui::link::decode;
use crate::lessons::{bundled, replay};
use crate::load::{Loaded, SceneSource};
use crate::measure::ab::{self, Heatmap, SideOptions};
use crate::measure::benchmark::{self, RunOptions, Stop};
use crate::measure::study::{self, Param, Study, Subject};
use crate::reports::study_table;

use super::target;

/// The page mode `query` asks for, if any. (`web/index.html` knows the
/// modes' keys too: it asks no WebGL for them.)
pub(crate) fn asked(query: &str) -> Option<PageMode> {
    let pairs: Vec<(&str, &str)> = (query.strip_prefix('?')?.split('&'))
        .map(|pair| pair.split_once('=').unwrap_or((pair, "")))
        .collect();
    if pairs == [("replay", "")] {
        return Some(PageMode::Replay);
    }
    let value = |key: &str| pairs.iter().find(|(k, _)| *k == key).map(|(_, v)| *v);
    if let Some(scene) = value("compare") {
        let flags = |side| value(side).map_or(Some(String::new()), decode);
        return Some(PageMode::Compare {
            scene: decode(scene)?,
            a: flags("a")?,
            b: flags("b")?,
        });
    }
    if let Some(scene) = value("study") {
        return Some(PageMode::Study {
            scene: decode(scene)?,
            param: decode(value("param").unwrap_or("depth"))?,
            values: decode(value("values").unwrap_or("1..3"))?,
        });
    }
    let scene = value("bench")?.to_string();
    // `workers` is web/index.html's: the pool is made before the module runs.
    let count = |key, default| value(key).and_then(|r| r.parse().ok()).unwrap_or(default);
    Some(PageMode::Bench {
        scene,
        runs: count("runs", 5),
        warmup: count("warmup", WARMUP_FRAMES),
    })
}

/// A page that shows words instead of the window.
#[derive(Debug, Clone)]
pub(crate) enum PageMode {
    /// Every bundled lesson replayed, step by step.
    Replay,
    /// `workbench bench --structures bvh --runs RUNS`'s frame of a scene:
    /// a bundled one by name, else `scenes/NAME.p3f` beside the page. The
    /// page starts one worker more than `&workers=N` asks for, which this
    /// task blocks while it waits for each frame. `warmup` frames are
    /// rendered first, untimed ([`WARMUP_FRAMES`]).
    Bench {
        scene: String,
        runs: usize,
        warmup: usize,
    },
    /// `workbench compare SCENE --a A --b B`'s metrics, the scene found
    /// as for [`PageMode::Bench`].
    Compare { scene: String, a: String, b: String },
    /// `workbench sweep SCENE --param PARAM --values VALUES --structures
    /// grid,bvh --runs 1`, run as the Studies window runs it (on a worker,
    /// refused without them), its chart drawn there and downloaded.
    Study {
        scene: String,
        param: String,
        values: String,
    },
}

impl PageMode {
    /// Runs the mode on the page's workers, saying its lines in the
    /// page's `#status` as they come and, at the end, its verdict in
    /// `<body data-replay>` (`passed`, `failed: N steps`) or
    /// `<body data-bench>` (the rays per second, or `error: …`).
    pub(crate) async fn run(self) -> Result<(), JsValue> {
        let (tx, rx) = mpsc::channel();
        let (attribute, spawned) = match self {
            PageMode::Replay => (
                "data-replay",
                target::spawn("lesson replay", move || replay_all(&tx)),
            ),
            PageMode::Bench {
                scene,
                runs,
                warmup,
            } => {
                let source = scene_source(scene).await?;
                let spawned = target::spawn("bench", move || bench(source, runs, warmup, &tx));
                ("data-bench", spawned)
            }
            PageMode::Compare { scene, a, b } => {
                let source = scene_source(scene).await?;
                let spawned = target::spawn("compare", move || compare(source, &a, &b, &tx));
                ("data-compare", spawned)
            }
            PageMode::Study {
                scene,
                param,
                values,
            } => {
                let source = scene_source(scene).await?;
                let spawned = target::spawn_long("study", move || {
                    study(source, &param, &values, &tx);
                });
                ("data-study", spawned)
            }
        };
        spawned.map_err(|e| JsValue::from_str(&e.to_string()))?;
        let mut said = String::new();
        loop {
            let mut finished = None;
            for line in rx.try_iter() {
                match line {
                    Said::Line(line) => said.push_str(&format!("{line}\n")),
                    Said::Finished(verdict) => finished = Some(verdict),
                }
            }
            show(&said, None);
            super::download::give_downloads();
            if let Some(verdict) = finished {
                show(&said, Some((attribute, &verdict)));
                return Ok(());
            }
            pause(100).await?;
        }
    }
}

/// What a page mode says as it goes.
enum Said {
    Line(String),
    /// The verdict, for the page's attribute.
    Finished(String),
}

/// Untimed frames a page benchmark renders first. V8 runs a module's
/// functions on its baseline compiler until its optimising tier has
/// compiled them, on background threads that take the cores the workers
/// render on: timed over the page's first five frames, two workers were
/// no faster than one on the 2-core VM; over thirty, 1.7 times as fast
/// (docs/PERFORMANCE.md).
const WARMUP_FRAMES: usize = 10;

/// Times the benchmark frame of `source` with the BVH, `runs` times,
/// after `warmup` frames untimed.
fn bench(source: SceneSource, runs: usize, warmup: usize, tx: &mpsc::Sender<Said>) {
    let say = |line: String| {
        let _ = tx.send(Said::Line(line));
    };
    let measured = (|| {
        let loaded = Loaded::read(source, &[], &mut |_| {})?;
        let settings = benchmark::frame_settings(&loaded.scene);
        let cases = benchmark::structures(&settings, &[AccelKind::Bvh], Encoding::default());
        // This task holds one worker while it waits for each frame.
        say(format!(
            "{}: {}x{}, {runs} run(s) after {warmup} untimed, {} worker(s) rendering",
            loaded.source.label(),
            settings.width,
            settings.height,
            rayon::current_num_threads() - 1
        ));
        let cancel = AtomicBool::new(false);
        let frames = |runs| {
            let options = RunOptions {
                runs,
                threads: None,
            };
            benchmark::run(&loaded.world, &cases, options, &cancel, &mut |_| {})
        };
        if warmup > 0 {
            frames(warmup)?;
        }
        let outcome = frames(runs)?;
        let measured = outcome.measurements.into_iter().next();
        measured.context("no frame was measured")
    })();
    let verdict = measured.map(|m| {
        let times: Vec<String> = m
            .times
            .iter()
            .map(|t| format!("{:.3}", t.as_secs_f64()))
            .collect();
        say(format!(
            "bvh: median {:.4} s of {} s, {} rays, {:.0} rays/s",
            m.median().as_secs_f64(),
            times.join(", "),
            m.rays(),
            m.rays_per_second()
        ));
        format!("{:.0}", m.rays_per_second())
    });
    conclude(tx, "benchmark", verdict);
}

/// How each measuring mode ends: `done`'s verdict sent, or why it could
/// not be had said (`cannot WHAT: …`) with the verdict `error: …`.
fn conclude(tx: &mpsc::Sender<Said>, what: &str, done: anyhow::Result<String>) {
    let verdict = done.unwrap_or_else(|e| {
        let _ = tx.send(Said::Line(format!("cannot {what}: {e:#}")));
        format!("error: {e:#}")
    });
    let _ = tx.send(Said::Finished(verdict));
}

/// Measures what `workbench compare` does of `source` with sides `a` and
/// `b` (`workbench render` flags each), and says the metrics: the
/// verdict is `{"mse": …, "psnr": …, "flip": …}`, as the command's JSON.
fn compare(source: SceneSource, a: &str, b: &str, tx: &mpsc::Sender<Said>) {
    let say = |line: String| {
        let _ = tx.send(Said::Line(line));
    };
    let measured = (|| {
        let loaded = Loaded::read(source, &[], &mut |_| {})?;
        let (base, encoding) = (SettingsArgs::default(), EncodingArgs::default());
        let a = side_from_flags(&loaded, "a", a, &base, &encoding)?;
        let b = side_from_flags(&loaded, "b", b, &base, &encoding)?;
        let options = SideOptions {
            threads: None,
            views: false,
            b_matches: None,
        };
        let cancel = AtomicBool::new(false);
        let worlds = [&a.world, &b.world];
        let compared = ab::run(
            worlds,
            a.case,
            b.case,
            options,
            Heatmap::Flip,
            &cancel,
            &mut |_| {},
        );
        compared?.context("the comparison was cancelled")
    })();
    let verdict = measured.map(|c| {
        let m = &c.metrics;
        say(format!("A: {}\nB: {}", c.labels.0, c.labels.1));
        say(format!(
            "MSE {:.6}, PSNR {:.4} dB, FLIP {:.6}",
            m.mse, m.psnr, m.flip
        ));
        serde_json::json!({ "mse": m.mse, "psnr": m.psnr, "flip": m.flip }).to_string()
    });
    conclude(tx, "compare", verdict);
}

/// Runs a one-run study of `param` over `values` on `source` with the
/// grid and the BVH, draws its chart and gives it as a download
/// (`study-PARAM-SCENE.png`); the verdict is `drawn: …`, or why not.
fn study(source: SceneSource, param: &str, values: &str, tx: &mpsc::Sender<Said>) {
    let say = |line: String| {
        let _ = tx.send(Said::Line(line));
    };
    let drawn = (|| {
        let param: Param = param.parse().map_err(anyhow::Error::msg)?;
        let loaded = Loaded::read(source, &[], &mut |_| {})?;
        let name = loaded.source.label();
        let mut base = RenderSettings::from_scene(&loaded.scene);
        base.antialiasing = false;
        let study = Study {
            param,
            values: study::values::parse(values)?,
            structures: vec![AccelKind::Grid, AccelKind::Bvh],
            options: RunOptions {
                runs: 1,
                threads: None,
            },
            encoding: Encoding::default(),
            reference_samples: None,
        };
        let subject = Subject::Scene {
            world: loaded.world,
            base,
        };
        study.check(&subject)?;
        let stop = AtomicBool::new(false);
        let stop = Stop {
            now: &stop,
            after_frame: &stop,
        };
        let outcome = study::run(&study, &subject, stop, &mut |_| {})?;
        for line in study_table::summary(param, &outcome.points) {
            say(line);
        }
        let png = study_plot::chart_png(param, &outcome.points, &name)?;
        let name = study_plot::chart_file_name(param, &name);
        super::download::SaveTo::named(name).write(&png)?;
        anyhow::Ok(format!("drawn: a PNG of {} bytes", png.len()))
    })();
    conclude(tx, "draw the study's chart", drawn);
}

/// Where scene `name` is read from: the embedded scene of that name, else
/// `scenes/NAME.p3f` beside the page.
async fn scene_source(name: String) -> Result<SceneSource, JsValue> {
    Ok(match crate::bundled::find(&name) {
        Some(_) => SceneSource::Bundled(name),
        None => {
            let text = fetch_text(&format!("scenes/{name}.p3f")).await?;
            SceneSource::Written { name, text }
        }
    })
}

/// The text at `url` (relative to the page), or why not.
async fn fetch_text(url: &str) -> Result<String, JsValue> {
    let bytes = super::web_link::fetched(url, &Default::default()).await?;
    String::from_utf8(bytes).map_err(|_| JsValue::from_str(&format!("{url}: not UTF-8 text")))
}

fn replay_all(tx: &mpsc::Sender<Said>) {
    let say = |line: String| {
        let _ = tx.send(Said::Line(line));
    };
    let lessons = match bundled::all() {
        Ok(lessons) => lessons,
        Err(e) => {
            say(format!("the bundled lessons do not read: {e}"));
            let _ = tx.send(Said::Finished("failed: the lessons do not read".into()));
            return;
        }
    };
    let mut failures = 0;
    for lesson in &lessons {
        say(format!(
            "{} (chapter {}): {}",
            lesson.name, lesson.chapter, lesson.title
        ));
        let count = lesson.steps.len();
        let walked = replay::replay(lesson, &mut |i, step| match step.failure() {
            None => say(format!("  step {}/{count} {}: pass", i + 1, step.title)),
            Some(why) => say(format!(
                "  step {}/{count} {}: FAIL: {why}",
                i + 1,
                step.title
            )),
        });
        match walked {
            Ok(steps) => failures += steps.iter().filter(|s| s.failure().is_some()).count(),
            Err(e) => {
                say(format!("  cannot be walked: {e:#}"));
                failures += 1;
            }
        }
    }
    say(format!(
        "{} lessons replayed, {failures} steps failed",
        lessons.len()
    ));
    let verdict = match failures {
        0 => "passed".to_string(),
        n => format!("failed: {n} steps"),
    };
    let _ = tx.send(Said::Finished(verdict));
}

/// Writes `text` into the page's `#status` (shown, left-aligned), and
/// the verdict into its `<body>` attribute once there is one.
fn show(text: &str, verdict: Option<(&str, &str)>) {
    let Some(document) = web_sys::window().and_then(|w| w.document()) else {
        return;
    };
    if let Some(status) = document.get_element_by_id("status") {
        status.set_text_content(Some(text));
        let _ = status.remove_attribute("hidden");
        let _ = status.set_attribute(
            "style",
            "white-space: pre; text-align: left; align-items: flex-start; overflow: auto",
        );
    }
    if let (Some(body), Some((attribute, verdict))) = (document.body(), verdict) {
        let _ = body.set_attribute(attribute, verdict);
    }
}

/// Waits `ms` milliseconds without holding the page's thread.
async fn pause(ms: i32) -> Result<(), JsValue> {
    let promise = js_sys::Promise::new(&mut |resolve, _| {
        if let Some(window) = web_sys::window() {
            let _ = window.set_timeout_with_callback_and_timeout_and_arguments_0(&resolve, ms);
        }
    });
    wasm_bindgen_futures::JsFuture::from(promise)
        .await
        .map(drop)
}
