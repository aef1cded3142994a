//! The engine against real scenes and jobs: failures reported once, load
//! progress, wakes, and settings held back during a build.

use std::sync::atomic::{AtomicU32, Ordering};

use tracer::accel::AccelKind;
use tracer::render::Encoding;

use super::*;

/// Polls the engine until `done` holds ([`tracer::waiting::wait_until`]).
fn wait_until(engine: &mut Engine, done: impl Fn(&mut Engine) -> bool) {
    tracer::waiting::wait_until("the engine", || done(engine));
}

#[test]
fn a_panicking_render_is_reported_once_and_the_next_render_works() {
    // The wake-up callback runs on the render threads; its third call
    // panics, standing for a bug in the tracer.
    let calls = Arc::new(AtomicU32::new(0));
    let counter = calls.clone();
    let mut engine = Engine::new(Arc::new(move || {
        if counter.fetch_add(1, Ordering::Relaxed) == 2 {
            panic!("a bug in the tracer");
        }
    }));
    engine.load(SceneSource::Bundled("balls_low".into()));
    wait_until(&mut engine, |e| e.poll_load().is_some());
    let settings = RenderSettings {
        width: 64,
        height: 64,
        ..RenderSettings::from_scene(&engine.scene().unwrap().scene)
    };
    engine.render(&settings).unwrap();
    wait_until(&mut engine, |e| {
        matches!(e.activity(), Activity::Job(JobState::Failed(_)))
    });
    let failure = engine.take_failure().expect("the failure");
    assert!(failure.contains("a bug in the tracer"), "{failure}");
    assert_eq!(engine.take_failure(), None, "reported once");

    engine.restart(&settings).unwrap();
    wait_until(&mut engine, |e| {
        e.activity() == Activity::Job(JobState::Done)
    });
    assert_eq!(engine.take_failure(), None);
    let snapshot = engine.snapshot(Encoding::Linear).unwrap();
    assert_eq!(snapshot.stats.passes_done, snapshot.stats.passes_target);
}

#[test]
fn a_large_mesh_reports_how_much_is_read_while_it_loads() {
    // About 10 MB of OBJ: progress comes every 4 MB.
    let dir = tracer::scratch::Scratch::new("engine-mesh");
    let path = dir.join("big.obj");
    let mut text = String::new();
    for i in 0..150_000 {
        let x = i as f32 * 1e-4;
        text += &format!(
            "v {x:.6} {:.6} 0.000000\nv {x:.6} 1.000000 0.500000\n",
            x * 0.5
        );
    }
    for i in 0..149_999 {
        text += &format!("f {} {} {}\n", 2 * i + 1, 2 * i + 2, 2 * i + 3);
    }
    std::fs::write(&path, text).unwrap();
    let mut engine = Engine::new(Arc::new(|| {}));
    engine.load(SceneSource::File(path));
    // The last fraction stays until the load is taken.
    wait_until(
        &mut engine,
        |e| matches!(e.activity(), Activity::Loading { fraction: Some(f), .. } if f > 0.0),
    );
    let Activity::Loading { name, fraction } = engine.activity() else {
        panic!("still loading until taken");
    };
    assert!(
        name.contains("big.obj") && fraction.unwrap() <= 1.0,
        "{name}"
    );
    wait_until(&mut engine, |e| e.poll_load().is_some());
    assert_eq!(engine.scene().unwrap().world.counts.triangles, 149_999);
}

/// An engine on the bundled scene `name`, counting its paced and its
/// immediate wakes from the render, not the scene load's: the loader
/// thread wakes the window too (its last wake may come after the load is
/// taken), which would meet any "the render woke it" check by itself.
fn counting_engine(name: &str) -> (Arc<AtomicU32>, Arc<AtomicU32>, Engine) {
    let paced = Arc::new(AtomicU32::new(0));
    let at_once = Arc::new(AtomicU32::new(0));
    let counting = |count: &Arc<AtomicU32>| -> Wake {
        let count = count.clone();
        Arc::new(move || {
            if std::thread::current().name() != Some(loader::THREAD_NAME) {
                count.fetch_add(1, Ordering::Relaxed);
            }
        })
    };
    let mut engine = Engine::with_wakes(counting(&paced), counting(&at_once));
    engine.load(SceneSource::Bundled(name.into()));
    wait_until(&mut engine, |e| e.poll_load().is_some());
    (paced, at_once, engine)
}

#[test]
fn the_last_pass_wakes_the_window_at_once() {
    let (paced, at_once, mut engine) = counting_engine("balls_low");
    let settings = RenderSettings {
        width: 32,
        height: 32,
        antialiasing: true,
        samples: 2,
        ..RenderSettings::from_scene(&engine.scene().unwrap().scene)
    };
    engine.render(&settings).unwrap();
    wait_until(&mut engine, |e| {
        e.activity() == Activity::Job(JobState::Done)
    });
    assert!(engine.is_complete());
    assert!(paced.load(Ordering::Relaxed) > 0, "tiles wake at the pace");
    // The last pass's report and the job's end.
    assert!(at_once.load(Ordering::Relaxed) >= 1);

    // A render that keeps refining is never complete.
    let refining = RenderSettings {
        keep_refining: true,
        ..settings
    };
    engine.render(&refining).unwrap();
    assert!(!engine.is_complete(), "a new job starts incomplete");
    wait_until(&mut engine, |e| {
        e.snapshot(Encoding::Linear).unwrap().stats.passes_done > 5
    });
    assert!(!engine.is_complete());
}

#[test]
fn new_settings_wait_for_the_structure_being_built_instead_of_building_another() {
    let (_, at_once, mut engine) = counting_engine("mesh_large");
    // Held before its build, the first job is surely still building when
    // new settings come, however fast the machine.
    engine.set_paused(true);
    // Refining for ever: the last pass never wakes the window at once.
    let settings = RenderSettings {
        width: 24,
        height: 24,
        keep_refining: true,
        ..RenderSettings::from_scene(&engine.scene().unwrap().scene)
    };
    let moved = RenderSettings {
        ambient: settings.ambient + 0.1,
        ..settings.clone()
    };
    engine.render(&settings).unwrap();
    assert_eq!(engine.activity(), Activity::Job(JobState::Building));
    engine.render(&moved).unwrap();
    assert_eq!(engine.version().0, 1, "no second job, no second build");
    assert_eq!(engine.activity(), Activity::Job(JobState::Building));
    engine.set_paused(false);
    // The window calls again every frame; the build's report wakes it.
    wait_until(&mut engine, |e| {
        e.render(&moved).unwrap();
        e.version().0 == 2
    });
    assert!(at_once.load(Ordering::Relaxed) > 0, "woken at once");
    assert_ne!(
        engine.activity(),
        Activity::Job(JobState::Building),
        "the new job has the structure already"
    );
    assert_eq!(engine.settings(), Some(&moved));
    // A change of structure does not wait.
    let grid = RenderSettings {
        accel: AccelKind::Grid,
        ..moved.clone()
    };
    engine.render(&grid).unwrap();
    assert_eq!(engine.version().0, 3);
}

/// `text` applied to the engine's scene and world, as `Side::apply` does:
/// the edited scene and which shapes changed.
fn edited(engine: &Engine, text: &str) -> (Loaded, ShapeChange) {
    let loaded = engine.scene().expect("a scene");
    let mut scene = loaded.scene.clone();
    let edit = tracer::scene::edit::Edit::parse_in(text, &scene).unwrap();
    edit.apply(&mut scene).unwrap();
    let mut world = (*loaded.world).clone();
    let change = world.update_shapes(&scene, &edit);
    let loaded = Loaded {
        scene,
        world: Arc::new(world),
        ..loaded.clone()
    };
    (loaded, change)
}

#[test]
fn a_move_refits_the_structure_and_the_next_job_builds_nothing() {
    let mut engine = Engine::new(Arc::new(|| {}));
    engine.load(SceneSource::Bundled("balls_low".into()));
    wait_until(&mut engine, |e| e.poll_load().is_some());
    let settings = RenderSettings {
        width: 32,
        height: 32,
        accel: AccelKind::Bvh,
        ..RenderSettings::from_scene(&engine.scene().unwrap().scene)
    };
    engine.render(&settings).unwrap();
    wait_until(&mut engine, |e| {
        e.activity() == Activity::Job(JobState::Done)
    });
    let built = engine.index().expect("the job's structure");

    // A sphere nudged: the structure is refitted, and the next job renders
    // over it at once, with no Building phase. Held before its first tile
    // (a job that had to build would hold in Building), so a fast job
    // cannot be Done before the test looks.
    let (scene, change) = edited(&engine, "object 2 translate 0.01 0 0");
    assert!(matches!(change, ShapeChange::InPlace(_)), "{change:?}");
    engine.edit_scene(scene, change);
    let refit = engine.index().expect("refitted");
    assert!(!Arc::ptr_eq(&refit, &built));
    engine.set_paused(true);
    engine.render(&settings).unwrap();
    assert_eq!(engine.activity(), Activity::Job(JobState::Rendering));
    assert!(Arc::ptr_eq(&engine.index().unwrap(), &refit));
    engine.set_paused(false);
    wait_until(&mut engine, |e| {
        e.activity() == Activity::Job(JobState::Done)
    });

    // A material edit keeps it as it is.
    let (scene, change) = edited(&engine, "object 2 kd 0.5");
    assert_eq!(change, ShapeChange::None);
    engine.edit_scene(scene, change);
    assert!(Arc::ptr_eq(&engine.index().unwrap(), &refit));

    // A sphere made a box: built anew by the next job.
    let (scene, change) = edited(&engine, "object 2 shape box 0 0 0 0.1 0.1 0.1");
    assert_eq!(change, ShapeChange::Renumbered);
    engine.edit_scene(scene, change);
    assert!(engine.index().is_none());
    engine.render(&settings).unwrap();
    wait_until(&mut engine, |e| {
        e.activity() == Activity::Job(JobState::Done)
    });
    let rebuilt = engine.index().expect("built again");
    assert!(!Arc::ptr_eq(&rebuilt, &refit));
}
