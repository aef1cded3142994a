//! The window driven as a user would, with `egui_kittest`: clicks on
//! labelled widgets, key presses, dropped files. Each test checks what the
//! renderer was asked to do, not only what the widgets show.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::thread::sleep;
use std::time::{Duration, Instant};

use eframe::App;
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use tracer::accel::AccelKind;
use tracer::render::{Budget, Encoding, JobState, RenderSettings, Snapshot};
use workbench::gui::{Activity, CompareLayout, Side, WorkbenchApp};
use workbench::load::SceneSource;

use crate::harness::{
    DroppedBytes, DroppedPath, WINDOW, broken_scene, drawn, is_done, ready_window, small_window,
    wait_for, window,
};

/// The window on the bundled `balls_low`, rendered small so tests are quick.
/// Waits until the render is done and its last image is drawn (uploads
/// are throttled).
fn wait_for_final_image(harness: &mut Harness<'static, WorkbenchApp>) {
    wait_for(harness, "the render to finish", is_done);
    wait_for(harness, "the final image on screen", |app| {
        app.is_display_current() && app.is_catalog_complete()
    });
    harness.step();
}

fn render_settings(harness: &Harness<'static, WorkbenchApp>) -> RenderSettings {
    harness
        .state()
        .engine()
        .settings()
        .cloned()
        .expect("a render job")
}

/// Runs enough frames for a command to reach the engine.
fn settle(harness: &mut Harness<'static, WorkbenchApp>) {
    harness.run_steps(3);
}

#[test]
fn the_window_opens_the_requested_scene_and_renders_it() {
    let mut harness = ready_window(WINDOW);
    wait_for(&mut harness, "the render to finish", is_done);
    // The engine renders the scene asked for (the default is the showcase),
    // at its resolution (512 x 512) times the scale of 1/8.
    let scene = harness.state().engine().scene().expect("a scene");
    assert_eq!(scene.source, SceneSource::Bundled("balls_low".into()));
    assert_eq!(scene.world.counts.objects(), 12, "balls_low's objects");
    let settings = render_settings(&harness);
    assert_eq!((settings.width, settings.height), (64, 64));
}

#[test]
fn each_toggle_changes_the_renderer_by_its_label_and_by_its_key() {
    type Flag = fn(&RenderSettings) -> bool;
    let toggles: [(&str, egui::Key, Flag); 4] = [
        ("Anti-aliasing", egui::Key::A, |s| s.antialiasing),
        ("Soft shadows", egui::Key::S, |s| s.soft_shadows),
        ("Depth of field", egui::Key::D, |s| s.depth_of_field),
        ("Uniform grid", egui::Key::G, |s| s.accel == AccelKind::Grid),
    ];
    let mut harness = ready_window(WINDOW);
    for (label, key, flag) in toggles {
        let before = flag(&render_settings(&harness));
        harness
            .get_by_role_and_label(Role::CheckBox, &format!("{label} ({key:?})"))
            .click();
        settle(&mut harness);
        assert_eq!(
            flag(&render_settings(&harness)),
            !before,
            "clicking {label}"
        );
        harness.key_press(key);
        settle(&mut harness);
        assert_eq!(flag(&render_settings(&harness)), before, "pressing {key:?}");
    }
}

#[test]
fn the_acceleration_choice_reaches_the_renderer() {
    let mut harness = ready_window(WINDOW);
    for (choice, kind) in [
        ("None", AccelKind::None),
        ("Uniform grid", AccelKind::Grid),
        ("BVH", AccelKind::Bvh),
    ] {
        harness.get_by_role(Role::ComboBox).click();
        settle(&mut harness);
        harness.get_by_role_and_label(Role::Button, choice).click();
        settle(&mut harness);
        assert_eq!(render_settings(&harness).accel, kind, "choosing {choice}");
    }
}

#[test]
fn sliders_change_the_render_settings() {
    let mut harness = ready_window(WINDOW);
    let before = render_settings(&harness);
    for label in ["Samples N", "Max depth", "Grid multiplier m"] {
        harness.get_by_role_and_label(Role::Slider, label).focus();
        settle(&mut harness);
        harness.key_press(egui::Key::ArrowRight);
        settle(&mut harness);
    }
    let after = render_settings(&harness);
    assert_eq!(after.samples, before.samples + 1);
    assert_eq!(after.max_depth, before.max_depth + 1);
    assert!(after.grid_multiplier > before.grid_multiplier);
}

#[test]
fn picking_a_scene_in_the_list_renders_it() {
    let mut harness = ready_window(WINDOW);
    harness.get_by_label("balls_medium").click();
    wait_for(&mut harness, "balls_medium to load", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source == SceneSource::Bundled("balls_medium".into()))
    });
    wait_for(&mut harness, "balls_medium to render", is_done);
}

#[test]
fn a_broken_scene_shows_its_error_and_the_current_scene_stays() {
    let (_folder, broken) = broken_scene("drop");

    let mut harness = ready_window(WINDOW);
    wait_for(&mut harness, "the first render", is_done);
    harness
        .input_mut()
        .dropped_files
        .push(Arc::new(DroppedPath(broken.clone())));
    wait_for(&mut harness, "the error", |app| app.error().is_some());
    let error = harness.state().error().unwrap().to_string();
    assert!(error.contains("broken.p3f"), "{error}");
    assert!(
        error.contains(":5:7"),
        "the error names line and column: {error}"
    );
    harness.get_by_label_contains("broken.p3f:5:7");
    let scene = harness.state().engine().scene().expect("the old scene");
    assert_eq!(scene.source, SceneSource::Bundled("balls_low".into()));
    assert_eq!(
        harness.state().engine().activity(),
        Activity::Job(JobState::Done)
    );
}

/// A file dropped on the web page is a name and its bytes, no file on
/// disk: a scene opens from its text under its name, a broken one is
/// refused at its line and column as on the desktop, a lesson opens set
/// up, and a mesh is said to need a file on disk.
#[test]
fn a_file_dropped_as_bytes_opens_from_its_text() {
    let mut harness = ready_window(WINDOW);
    let drop = |harness: &mut Harness<'static, WorkbenchApp>, name: &str, text: &str| {
        harness
            .input_mut()
            .dropped_files
            .push(Arc::new(DroppedBytes {
                name: name.into(),
                bytes: text.as_bytes().to_vec(),
            }));
    };
    let scene = "v from 0 0 5 at 0 0 0 up 0 1 0 angle 40 resolution 40 30\n\
                 l 0 5 5\nf 1 0 0 1 0 0 0 0 1 0 1\ns 0 0 0 1\n";
    drop(&mut harness, "dropped.p3f", scene);
    wait_for(&mut harness, "the dropped scene", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source.label() == "dropped.p3f")
    });
    wait_for(&mut harness, "its render", is_done);
    let view = harness.state().engine().scene().map(|s| s.scene.view.width);
    assert_eq!(view, Some(40), "the dropped text's own view");

    drop(&mut harness, "broken.p3f", &format!("{scene}s 0 0\n"));
    wait_for(&mut harness, "the error", |app| app.error().is_some());
    let error = harness.state().error().unwrap().to_string();
    assert!(error.contains("broken.p3f:5:"), "{error}");
    let shown = harness.state().engine().scene().map(|s| s.source.label());
    assert_eq!(shown.as_deref(), Some("dropped.p3f"), "the scene stays");

    drop(&mut harness, "bunny.obj", "v 0 0 0\n");
    wait_for(&mut harness, "the mesh refused", |app| {
        app.error()
            .is_some_and(|e| e.contains("bunny.obj: a mesh opens from a file on disk"))
    });

    let lesson = std::fs::read_to_string("../assets/lessons/shadows.toml").unwrap();
    drop(&mut harness, "my_shadows.toml", &lesson);
    wait_for(&mut harness, "the dropped lesson set up", |app| {
        app.lessons()
            .lesson()
            .is_some_and(|l| l.name == "my_shadows")
            && app
                .engine()
                .scene()
                .is_some_and(|s| s.source.label() == "my_shadows.p3f")
    });
}

#[test]
fn the_statistics_panel_shows_the_work_done() {
    let mut harness = ready_window(WINDOW);
    wait_for_final_image(&mut harness);
    for name in ["Rays", "  eye", "  shadow", "Intersection tests"] {
        let value = statistic(&harness, name);
        assert!(
            !value.is_empty() && value != "0",
            "{name} shows {value:?} after a finished render"
        );
    }
}

/// The value shown next to `name` in the statistics panel.
fn statistic(harness: &Harness<'static, WorkbenchApp>, name: &str) -> String {
    let texts: Vec<String> = harness
        .get_all_by_role(Role::Label)
        .filter_map(|n| n.accesskit_node().label().or(n.accesskit_node().value()))
        .collect();
    let at = texts
        .iter()
        .position(|t| t == name)
        .unwrap_or_else(|| panic!("no statistic {name:?} among {texts:?}"));
    texts[at + 1].clone()
}

/// Where the window snapshots live; `UPDATE_SNAPSHOTS=1 cargo test --test
/// gui` rewrites them on purpose (look at them before committing).
const SNAPSHOTS: &str = "tests/snapshots";

/// The window drawn by wgpu (Mesa's software Vulkan or GL on CI).
fn drawn_window() -> Harness<'static, WorkbenchApp> {
    let mut harness = window(
        Harness::builder().with_size([1100.0, 700.0]).wgpu(),
        None,
        Some(SceneSource::Bundled("balls_low".into())),
    );
    harness.state_mut().controls_mut().resolution_scale = 0.5;
    harness
}

/// Paints over values that change from run to run (times, speeds), so the
/// snapshot compares layout, labels and the deterministic image.
fn mask_timings(harness: &mut Harness<'static, WorkbenchApp>) {
    let mut rects = Vec::new();
    for name in [
        "Render time",
        "Last pass",
        "Rays per second",
        "  build time",
        "Scene load",
        "UI frames per second",
        "UI work per frame",
        "UI CPU per frame",
        "Redraw interval",
    ] {
        if let Some(rect) = value_rect(harness, name) {
            // To the panel's edge: the text's own width varies too.
            rects.push(rect.with_max_x(f32::INFINITY));
        }
    }
    rects.extend(
        harness
            .query_all_by_label_contains(" spp")
            .map(|n| n.rect())
            .collect::<Vec<_>>(),
    );
    // The pass plots, below the last row of the statistics.
    if let Some(last_row) = value_rect(harness, "Redraw interval") {
        let name = harness.get_by_label("Redraw interval").rect();
        rects.push(egui::Rect::from_min_max(
            egui::pos2(name.left(), last_row.bottom() + 2.0),
            egui::pos2(f32::INFINITY, f32::INFINITY),
        ));
    }
    for rect in rects {
        harness.mask(rect);
    }
}

/// The rectangle of the value shown next to `name` in the statistics.
fn value_rect(harness: &Harness<'static, WorkbenchApp>, name: &str) -> Option<egui::Rect> {
    let labels: Vec<_> = harness.get_all_by_role(Role::Label).collect();
    let at = labels.iter().position(|n| {
        n.accesskit_node()
            .label()
            .or(n.accesskit_node().value())
            .as_deref()
            == Some(name)
    })?;
    labels.get(at + 1).map(|n| n.rect())
}

/// Compares the window with the stored snapshot `name` as eframe shows it:
/// the harness renders over a transparent background, where eframe clears
/// the window with the app's clear colour (the panels' colour, which the
/// panels leave to the clear).
fn snapshot(harness: &mut Harness<'static, WorkbenchApp>, name: &str) {
    let mut image = drawn(harness);
    let visuals = harness.ctx.global_style().visuals.clone();
    let clear = harness.state().clear_color(&visuals).map(|c| c * 255.0);
    for pixel in image.pixels_mut() {
        // The render is premultiplied: what is left of each pixel's
        // coverage shows the clear colour.
        let cover = f32::from(pixel[3]) / 255.0;
        for (channel, under) in pixel.0.iter_mut().zip(clear) {
            *channel = (f32::from(*channel) + under * (1.0 - cover))
                .round()
                .min(255.0) as u8;
        }
    }
    egui_kittest::image_snapshot_options(
        &image,
        name,
        &egui_kittest::SnapshotOptions::new().output_path(SNAPSHOTS),
    );
}

#[test]
fn snapshot_of_a_finished_render() {
    let mut harness = drawn_window();
    wait_for(&mut harness, "the render to finish", is_done);
    // A few more frames: the last texture upload waits for its interval.
    wait_for_final_image(&mut harness);
    harness.run_steps(2);
    mask_timings(&mut harness);
    snapshot(&mut harness, "window_done");
}

#[test]
fn snapshot_while_rendering() {
    let mut harness = drawn_window();
    // A scene whose first pass lasts long enough to be held half done.
    harness
        .state_mut()
        .open(SceneSource::Bundled("balls_high".into()));
    wait_for(&mut harness, "balls_high", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source == SceneSource::Bundled("balls_high".into()))
    });
    {
        let controls = harness.state_mut().controls_mut();
        controls.render.antialiasing = true;
        controls.render.samples = 16;
        controls.render.keep_refining = true;
        // 1024 x 1024.
        controls.resolution_scale = 2.0;
    }
    // How far the render got changes every count in the statistics; the
    // finished-render snapshot covers that panel.
    harness.state_mut().set_statistics_shown(false);
    // The render never ends (it keeps refining): the list is counted now,
    // not after its delay on the window's stopped clock.
    harness.state_mut().set_catalog_delay(Duration::ZERO);
    wait_for(&mut harness, "the scene list", |app| {
        app.is_catalog_complete() && app.engine().settings().is_some()
    });
    // A fresh render (drawn over the last one, which the mask hides),
    // which pauses itself after its first tiles whatever the machine.
    harness.state_mut().pause_renders_after_tiles(Some(8));
    harness.key_press(egui::Key::R);
    let restarted = harness.state().engine().version().0 + 1;
    wait_for(&mut harness, "the first tiles, held, on screen", |app| {
        let engine = app.engine();
        engine.version().0 >= restarted && engine.is_paused() && app.is_display_current()
    });
    let shown = harness.state().shown().unwrap().clone();
    let covered = coverage(&shown);
    assert!(
        shown.stats.passes_done == 0 && covered > 0.0 && covered < 1.0,
        "the window shows some tiles of the first pass and not others: {} passes, {:.0}% covered",
        shown.stats.passes_done,
        covered * 100.0
    );
    assert_eq!(
        harness.state().engine().activity(),
        Activity::Job(JobState::Rendering)
    );
    harness.key_press(egui::Key::Space);
    harness.run_steps(2);
    // The image and the pass plots depend on how far the render got.
    let render = harness.get_by_role_and_label(Role::Image, "Render").rect();
    harness.mask(render);
    mask_timings(&mut harness);
    snapshot(&mut harness, "window_rendering");
}

#[test]
fn snapshot_with_an_error_shown() {
    // A relative path from the test's working directory (app/), so the
    // message, and how it wraps, is the same on every machine.
    let broken = PathBuf::from("tests/bad_scenes/camera_angle_180.p3f");
    let mut harness = drawn_window();
    wait_for(&mut harness, "the render to finish", is_done);
    harness.state_mut().open(SceneSource::File(broken.clone()));
    wait_for(&mut harness, "the error", |app| app.error().is_some());
    wait_for_final_image(&mut harness);
    harness.run_steps(2);
    harness.get_by_label_contains("camera_angle_180.p3f:3:7");
    mask_timings(&mut harness);
    snapshot(&mut harness, "window_error");
}

fn side_b<'a>(harness: &'a Harness<'static, WorkbenchApp>) -> &'a Side {
    harness.state().side_b().expect("compare mode is on")
}

/// The comparison's metrics, once measured.
fn metrics(harness: &Harness<'static, WorkbenchApp>) -> workbench::measure::ab::Metrics {
    let comparison = harness.state().comparison().expect("compare mode is on");
    comparison
        .metrics()
        .expect("measured")
        .clone()
        .expect("no error")
}

fn both_done_and_measured(app: &WorkbenchApp) -> bool {
    app.comparison().is_some_and(|c| c.metrics().is_some()) && is_done(app)
}

/// B's budget, when its job has one.
fn b_budget(app: &WorkbenchApp) -> Option<Budget> {
    app.side_b()?.engine.settings()?.adaptive()?.budget
}

/// Compare mode's B at A's cost: "equal samples" makes B adaptive,
/// renders it once A is done and stops it at A's sample total; "equal
/// time" gives it A's render time as its budget (its mechanism; what a
/// time budget does is the tracer's test, without a clock).
#[test]
fn compare_mode_matches_adaptive_b_to_a() {
    let mut harness = ready_window(WINDOW);
    harness.key_press(egui::Key::B);
    settle(&mut harness);
    harness
        .get_by_role_and_label(Role::Button, "equal samples")
        .click();
    wait_for(&mut harness, "B at A's samples", |app| {
        is_done(app) && matches!(b_budget(app), Some(Budget::Samples(_)))
    });
    let a = harness.state().engine().stats().unwrap();
    let b = side_b(&harness).engine.stats().unwrap();
    assert!(
        a.adaptive.is_none() && b.adaptive.is_some(),
        "A uniform, B adaptive"
    );
    assert_eq!(
        b_budget(harness.state()),
        Some(Budget::Samples(a.samples_taken()))
    );
    assert!(b.samples_taken() <= a.samples_taken());
    harness.get_by_label("Mean spp");

    harness
        .get_by_role_and_label(Role::Button, "equal time")
        .click();
    wait_for(&mut harness, "B at A's time", |app| {
        is_done(app) && matches!(b_budget(app), Some(Budget::Time(_)))
    });
    let a = harness.state().engine().stats().unwrap();
    assert_eq!(b_budget(harness.state()), Some(Budget::Time(a.render_time)));
}

#[test]
fn compare_mode_renders_b_beside_a_and_measures_the_difference() {
    let mut harness = ready_window(WINDOW);
    harness.key_press(egui::Key::B);
    settle(&mut harness);
    // B starts as a copy of A; the keys now edit B.
    assert_eq!(&side_b(&harness).controls, harness.state().controls());
    harness.key_press(egui::Key::G);
    settle(&mut harness);
    assert_eq!(
        side_b(&harness).engine.settings().unwrap().accel,
        AccelKind::Grid
    );
    assert_eq!(render_settings(&harness).accel, AccelKind::Bvh, "A stays");

    // Grid and BVH find the same hits: the same image.
    wait_for(
        &mut harness,
        "both sides and their metrics",
        both_done_and_measured,
    );
    let same = metrics(&harness);
    assert_eq!(same.mse, 0.0);
    assert_eq!(same.flip, 0.0);
    assert!(
        harness
            .query_all_by_label_contains("B: grid on")
            .next()
            .is_some(),
        "B is labelled by what differs"
    );

    // Soft shadows on B change the image.
    harness
        .get_by_role_and_label(Role::CheckBox, "Soft shadows (S)")
        .click();
    settle(&mut harness);
    wait_for(&mut harness, "B with soft shadows", |app| {
        both_done_and_measured(app)
            && app
                .side_b()
                .is_some_and(|b| b.engine.settings().is_some_and(|s| s.soft_shadows))
    });
    let differ = metrics(&harness);
    assert!(differ.mse > 0.0 && differ.flip > 0.0, "{differ:?}");
    assert!(differ.psnr.is_finite());

    for layout in CompareLayout::ALL {
        harness
            .get_by_role_and_label(Role::Button, layout.label())
            .click();
        settle(&mut harness);
        assert_eq!(harness.state().comparison().unwrap().layout, layout);
    }
    wait_for(&mut harness, "the difference map", |app| {
        app.comparison().is_some_and(|c| c.difference().is_some())
    });

    // Swap: A now has B's settings, renders and all.
    harness
        .get_by_role_and_label(Role::Button, "Swap A and B")
        .click();
    settle(&mut harness);
    let a = render_settings(&harness);
    assert!(a.soft_shadows && a.accel == AccelKind::Grid);
    assert!(!side_b(&harness).engine.settings().unwrap().soft_shadows);
    // Copy A to B makes them equal again.
    harness.key_press_modifiers(egui::Modifiers::SHIFT, egui::Key::B);
    settle(&mut harness);
    assert_eq!(
        side_b(&harness).engine.settings(),
        harness.state().engine().settings()
    );
}

#[test]
fn the_benchmark_matrix_fills_every_row_with_consistent_images() {
    let mut harness = ready_window(WINDOW);
    harness.key_press(egui::Key::M);
    settle(&mut harness);
    let runs = harness.get_by_role_and_label(Role::Slider, "runs each");
    runs.focus();
    settle(&mut harness);
    for _ in 0..4 {
        harness.key_press(egui::Key::ArrowLeft);
        settle(&mut harness);
    }
    harness.get_by_role_and_label(Role::Button, "Run").click();
    settle(&mut harness);
    assert!(harness.state().benchmark().is_running());
    wait_for(&mut harness, "the matrix", |app| {
        !app.benchmark().is_running()
    });
    let rows: Vec<_> = harness
        .state()
        .benchmark()
        .measurements()
        .cloned()
        .collect();
    assert_eq!(
        rows.len(),
        18,
        "3 structures x 2 shadow modes x 3 samplings"
    );
    for row in &rows {
        assert_eq!(row.times.len(), 1);
        assert_eq!(row.case.settings.width, 64);
    }
    // The same sampling gives the same image whatever the structure.
    for row in &rows {
        let twin = rows
            .iter()
            .find(|r| {
                r.case.settings.accel == AccelKind::Bvh
                    && r.case.file_stem().ends_with(
                        row.case
                            .file_stem()
                            .trim_start_matches(row.case.settings.accel.name()),
                    )
            })
            .expect("a BVH row of the same sampling");
        assert!(
            twin.image == row.image,
            "{} differs from {}",
            row.case.label,
            twin.case.label
        );
    }
    // Each sampling shows the scene (not a blank or a flat fill) and
    // differs from the plain one: soft shadows, anti-aliasing or the lens
    // doing nothing would fail here.
    let plain = &rows
        .iter()
        .find(|r| r.case.file_stem() == "bvh")
        .unwrap()
        .image;
    for row in rows
        .iter()
        .filter(|r| r.case.settings.accel == AccelKind::Bvh)
    {
        let colours: std::collections::HashSet<_> = row.image.pixels().map(|p| p.0).collect();
        assert!(
            colours.len() >= 32,
            "{}: {} colours",
            row.case.label,
            colours.len()
        );
        let changed = row
            .image
            .pixels()
            .zip(plain.pixels())
            .filter(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > 8))
            .count();
        let plain_row = row.case.file_stem() == "bvh";
        assert!(
            plain_row || changed >= 8,
            "{} differs from the plain image in only {changed} pixels",
            row.case.label
        );
    }
}

/// How long a window may stay without asking for a frame while its image
/// is not final: the workspace's one bound on a wait, far above any
/// progress interval (`MAX_PROGRESS_INTERVAL`, 2 s) and any pass of this
/// small render on a loaded machine; only a window that stopped asking
/// ever reaches it.
const QUIET: Duration = tracer::waiting::PATIENCE;

/// Frames as eframe schedules them: one only when the app or a render
/// thread asked for it, at the time asked; requests from before the last
/// frame are dropped and pending ones merge into the earliest, as eframe's
/// event loop does.
struct RepaintRequests(Arc<Mutex<Vec<(Instant, u64)>>>);

impl RepaintRequests {
    fn install(ctx: &egui::Context) -> Self {
        let requests = Arc::new(Mutex::new(Vec::new()));
        let sink = requests.clone();
        ctx.set_request_repaint_callback(move |info| {
            sink.lock()
                .unwrap()
                .push((Instant::now() + info.delay, info.current_cumulative_pass_nr));
        });
        Self(requests)
    }

    /// Waits until the next requested frame is due; false if none was asked
    /// for within [`QUIET`].
    fn wait_for_next(&self, ctx: &egui::Context) -> bool {
        let start = Instant::now();
        loop {
            let pass = ctx.cumulative_pass_nr();
            let due = {
                let mut requests = self.0.lock().unwrap();
                let due = requests
                    .iter()
                    .filter(|&&(_, nr)| pass == nr || pass == nr + 1)
                    .map(|&(at, _)| at)
                    .min();
                requests.clear();
                due
            };
            if let Some(due) = due {
                sleep(due.saturating_duration_since(Instant::now()));
                return true;
            }
            if start.elapsed() > QUIET {
                return false;
            }
            sleep(Duration::from_millis(2));
        }
    }
}

/// The window drawn by wgpu on `balls_low` at 64 x 64 with 2 x 2 samples
/// (four passes).
fn small_drawn_window() -> Harness<'static, WorkbenchApp> {
    let mut harness = drawn_window();
    let controls = harness.state_mut().controls_mut();
    controls.resolution_scale = 0.5;
    controls.render.antialiasing = true;
    controls.render.samples = 2;
    harness
}

/// Whether the text of the window says the render is done with every pass
/// on screen.
fn says_final(harness: &Harness<'static, WorkbenchApp>) -> bool {
    let Some(settings) = harness.state().engine().settings() else {
        return false;
    };
    let target = settings.samples_per_pixel();
    let all = format!("{target} / {target}");
    is_done(harness.state())
        && status_line(harness)
            .is_some_and(|s| s.contains(&format!("{all} spp")) && s.ends_with("done"))
        && statistic(harness, "Samples per pixel") == all
}

/// The status line under the image, once it shows an image's size.
fn status_line(harness: &Harness<'static, WorkbenchApp>) -> Option<String> {
    harness
        .query_all_by_label_contains(" spp")
        .find_map(|n| n.accesskit_node().label().or(n.accesskit_node().value()))
}

/// The share of `snapshot`'s pixels that have a sample.
fn coverage(snapshot: &Snapshot) -> f32 {
    let covered = snapshot.rgba.chunks(4).filter(|p| p[3] != 0).count();
    covered as f32 / (snapshot.width * snapshot.height).max(1) as f32
}

/// Where the viewport draws a render of `width` x `height` (fit to view).
fn image_rect(harness: &Harness<'static, WorkbenchApp>, width: u32, height: u32) -> egui::Rect {
    let view = harness.get_by_role_and_label(Role::Image, "Render").rect();
    let size = egui::vec2(width as f32, height as f32);
    let scale = (view.width() / size.x).min(view.height() / size.y);
    egui::Rect::from_center_size(view.center(), size * scale)
}

/// Asserts the last drawn frame shows `snapshot` in the viewport, pixel for
/// pixel (each image pixel sampled at its centre; magnification is nearest).
fn assert_viewport_shows(harness: &mut Harness<'static, WorkbenchApp>, snapshot: &Snapshot) {
    let rect = image_rect(harness, snapshot.width, snapshot.height);
    let frame = drawn(harness);
    let ppp = harness.ctx.pixels_per_point();
    let mut wrong = 0;
    for y in 0..snapshot.height {
        for x in 0..snapshot.width {
            let px = rect.min.x + (x as f32 + 0.5) * rect.width() / snapshot.width as f32;
            let py = rect.min.y + (y as f32 + 0.5) * rect.height() / snapshot.height as f32;
            let shown = frame.get_pixel((px * ppp) as u32, (py * ppp) as u32).0;
            let i = ((y * snapshot.width + x) * 4) as usize;
            let want = &snapshot.rgba[i..i + 3];
            if (0..3).any(|c| shown[c].abs_diff(want[c]) > 2) {
                wrong += 1;
            }
        }
    }
    assert_eq!(
        wrong, 0,
        "{wrong} pixels of the viewport differ from the render"
    );
}

#[test]
fn the_final_pass_is_drawn_when_frames_come_only_on_request() {
    let mut harness = small_drawn_window();
    let requests = RepaintRequests::install(&harness.ctx);
    // The frame the window paints when it opens; after it, eframe paints
    // only when asked.
    harness.step();
    while !says_final(&harness) {
        assert!(
            requests.wait_for_next(&harness.ctx),
            "the window stopped asking for frames before drawing the final image: {:?}, \
             status {:?}",
            harness.state().engine().activity(),
            status_line(&harness)
        );
        harness.step();
    }
    let last = harness
        .state()
        .engine()
        .snapshot(Encoding::Linear)
        .expect("a render");
    assert_eq!(last.stats.passes_done, last.stats.passes_target);
    assert_viewport_shows(&mut harness, &last);
}

/// The share of the image area showing the empty viewport's grey.
fn empty_share(harness: &mut Harness<'static, WorkbenchApp>, rect: egui::Rect) -> f32 {
    let frame = drawn(harness);
    let ppp = harness.ctx.pixels_per_point();
    let (mut empty, mut total) = (0, 0);
    let (x0, y0) = ((rect.min.x * ppp) as u32, (rect.min.y * ppp) as u32);
    let (x1, y1) = ((rect.max.x * ppp) as u32, (rect.max.y * ppp) as u32);
    for y in (y0 + 1..y1.saturating_sub(1)).step_by(2) {
        for x in (x0 + 1..x1.saturating_sub(1)).step_by(2) {
            let p = frame.get_pixel(x, y).0;
            empty += u32::from(p[..3] == [24, 24, 24]);
            total += 1;
        }
    }
    empty as f32 / total.max(1) as f32
}

#[test]
fn a_camera_move_never_shows_an_empty_view() {
    let mut harness = drawn_window();
    harness.state_mut().controls_mut().resolution_scale = 0.25;
    wait_for_final_image(&mut harness);
    let settings = render_settings(&harness);
    let rect = image_rect(&harness, settings.width, settings.height);
    let before = empty_share(&mut harness, rect);
    assert!(
        before < 0.01,
        "the finished render leaves {before:.3} empty"
    );

    let mut at = rect.center();
    harness.drag_at(at);
    harness.step();
    for frame in 0..12 {
        at += egui::vec2(7.0, 3.0);
        harness.hover_at(at);
        harness.step();
        let empty = empty_share(&mut harness, rect);
        assert!(
            empty < 0.01,
            "frame {frame} of the orbit shows {:.0}% of the view empty",
            empty * 100.0
        );
    }
    assert!(
        harness.state().engine().settings().unwrap().width < settings.width,
        "a preview renders while dragging"
    );
    harness.drop_at(at);
    // After the release the full resolution renders again, over the preview.
    tracer::waiting::wait_until("the render after the orbit", || {
        harness.step();
        let empty = empty_share(&mut harness, rect);
        assert!(
            empty < 0.01,
            "after the orbit, {:.0}% of the view is empty",
            empty * 100.0
        );
        is_done(harness.state()) && harness.state().is_display_current()
    });
}

/// On a software rasterizer every shaded fragment costs the render CPU:
/// the panels leave their background to the window's clear (the same
/// colour) instead of painting a panel-sized rectangle in every frame.
#[test]
fn the_panels_paint_no_background_of_their_own() {
    let mut harness = ready_window(WINDOW);
    harness.run_steps(2);
    let visuals = harness.ctx.global_style().visuals.clone();
    let clear = harness.state().clear_color(&visuals);
    assert_eq!(clear, visuals.panel_fill.to_normalized_gamma_f32());
    let backgrounds: Vec<egui::Rect> = harness
        .output()
        .shapes
        .iter()
        .filter_map(|clipped| match &clipped.shape {
            egui::Shape::Rect(rect) if rect.fill == visuals.panel_fill => Some(rect.rect),
            _ => None,
        })
        .filter(|rect| rect.area() > 40_000.0)
        .collect();
    assert!(
        backgrounds.is_empty(),
        "panel backgrounds painted: {backgrounds:?}"
    );
}

/// Under a finished image the viewport's grey would be painted only to be
/// covered, a view-sized rectangle of fragments a software rasterizer
/// shades in every frame: it is painted around the image only.
#[test]
fn the_viewport_paints_its_background_around_a_finished_image_only() {
    let mut harness = ready_window(WINDOW);
    wait_for_final_image(&mut harness);
    let settings = render_settings(&harness);
    let image = image_rect(&harness, settings.width, settings.height);
    let view = harness.get_by_role_and_label(Role::Image, "Render").rect();
    let grey: Vec<egui::Rect> = harness
        .output()
        .shapes
        .iter()
        .filter_map(|clipped| match &clipped.shape {
            egui::Shape::Rect(rect) if rect.fill == egui::Color32::from_gray(24) => Some(rect.rect),
            _ => None,
        })
        .collect();
    let under: f32 = grey
        .iter()
        .map(|r| r.intersect(image).area().max(0.0))
        .sum();
    assert!(
        under < 1.0,
        "{under} points of grey under the image: {grey:?}"
    );
    let around: f32 = grey.iter().map(|r| r.intersect(view).area().max(0.0)).sum();
    let margins = view.area() - image.intersect(view).area();
    assert!(
        (around - margins).abs() < 1.0,
        "grey {around} around the image, margins {margins}"
    );
}

/// Holds the first render after its first tile, so it is surely under way
/// when the test looks. The window must not have stepped yet: its scene
/// loads, and its first render starts, in later frames. (Pressing Space
/// instead raced the render: a 64 x 64 render could end before the key
/// arrived, and then nothing was ever held.)
fn hold_first_render(harness: &mut Harness<'static, WorkbenchApp>) {
    harness.state_mut().pause_renders_after_tiles(Some(1));
    wait_for(harness, "the first render, held", |app| {
        app.engine().is_paused() && app.engine().activity() == Activity::Job(JobState::Rendering)
    });
    harness.state_mut().pause_renders_after_tiles(None);
}

/// Counting the bundled scenes for the scene list (parsing a 262k-triangle
/// mesh among them) waits until the first render is done: it took 30-100
/// ms of a two-core machine during a 0.4 s render, at its lowest priority.
#[test]
fn the_scene_list_is_counted_after_the_first_render() {
    let mut harness = small_window(Harness::builder());
    // No deadline: only the end of the first render lets counting start.
    harness.state_mut().set_catalog_delay(Duration::MAX);
    hold_first_render(&mut harness);
    for _ in 0..10 {
        harness.step();
        assert!(
            !harness.state().is_catalog_started(),
            "the scene list is counted during the first render"
        );
    }
    harness.key_press(egui::Key::Space);
    wait_for(&mut harness, "the first render", |app| {
        // Done in this frame, the list may start counting in it too.
        is_done(app) || {
            assert!(
                !app.is_catalog_started(),
                "the scene list is counted during the first render ({:?})",
                app.engine().activity()
            );
            false
        }
    });
    // Started once the render is done; finishing, at the lowest priority
    // beside the other tests' renders, is the other tests' business.
    wait_for(&mut harness, "the scene list's counting", |app| {
        app.is_catalog_started()
    });
}

#[test]
fn the_scene_list_is_counted_by_its_deadline_even_during_a_render() {
    let mut harness = small_window(Harness::builder());
    harness.state_mut().set_catalog_delay(Duration::ZERO);
    hold_first_render(&mut harness);
    wait_for(&mut harness, "the counts during the held render", |app| {
        app.is_catalog_started() && app.engine().is_paused()
    });
}

/// A valid scene dropped on the window opens, and so does a bare mesh
/// (framed: the mesh and the ground plane added under it).
#[test]
fn a_dropped_scene_or_mesh_opens() {
    let dir = crate::support::scratch("drop-valid");
    let scene = crate::support::write(
        &dir,
        "floor.p3f",
        &crate::support::scenes::spheres_on_a_floor(32, 24, "", ""),
    );
    let mesh = crate::support::write(
        &dir,
        "tetra.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    );
    let mut harness = ready_window(WINDOW);
    for (dropped, objects) in [(scene, 3), (mesh, 2)] {
        harness
            .input_mut()
            .dropped_files
            .push(Arc::new(DroppedPath(dropped.clone())));
        wait_for(&mut harness, "the dropped file rendered", |app| {
            app.engine().scene().map(|s| &s.source) == Some(&SceneSource::File(dropped.clone()))
                && is_done(app)
        });
        let app = harness.state();
        assert!(app.error().is_none(), "{:?}", app.error());
        let scene = app.engine().scene().unwrap();
        assert_eq!(
            scene.world.counts.objects(),
            objects,
            "{}",
            dropped.display()
        );
    }
}
