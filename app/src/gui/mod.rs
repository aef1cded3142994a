//! The window: an egui/eframe app (wgpu renderer) around the progressive
//! renderer. Its parts, one folder each: `sides` (A and B: an engine, the
//! image on screen, the controls; the interface to the renderer), `app`
//! (the frame: arrivals, commands, saving), `panels` (drawing, over
//! narrow views of the state), `image` (the viewport and what is drawn
//! over it), `comparison` (compare mode's layout and measures), `editor`
//! (changing the scene: selection, the editor window, moving objects),
//! `windows` (ray tree, benchmark, studies, help) and `platform` (frame
//! pacing, CPU clocks, the software rasterizer, screenshots).

mod app;
mod commands;
mod comparison;
mod editor;
mod image;
mod lessons;
mod link;
mod observer;
mod panels;
mod platform;
mod sides;
mod windows;

#[cfg(not(target_family = "wasm"))]
use std::path::PathBuf;

pub use app::{FileDialog, FileQuestion, WorkbenchApp};
pub use commands::Command;
pub use comparison::{CompareLayout, Comparison, ReferenceImage};
pub use editor::{Editor, Pending};
pub use platform::clock::Clock;
#[cfg(not(target_family = "wasm"))]
use platform::screenshot::{ScreenshotOutcome, ScreenshotPlan};
pub use sides::{Activity, Controls, Engine, Side, SideId};

#[cfg(not(target_family = "wasm"))]
use crate::load::SceneSource;

/// The window's title, which names the folder eframe saves its state in
/// (`lessons::progress::window_state_file` looks there).
pub(crate) const TITLE: &str = "Whitted Workbench";

/// Opens the window on `scene` (or the last scene, or the bundled default),
/// with the observer view on when `observer`, the lessons of
/// `lesson_folder` listed and the first set up, the lesson `lesson` (a file
/// or a bundled lesson's name; if given) set up instead, and runs until it is closed or until the
/// screenshot of `screenshot` is taken.
#[cfg(not(target_family = "wasm"))]
pub fn run(
    scene: Option<PathBuf>,
    screenshot: Option<ScreenshotPlan>,
    observer: bool,
    lesson: Option<PathBuf>,
    lesson_folder: Option<PathBuf>,
) -> anyhow::Result<()> {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(TITLE)
            .with_inner_size([1280.0, 820.0])
            .with_min_inner_size([640.0, 400.0])
            .with_drag_and_drop(true),
        renderer: eframe::Renderer::Wgpu,
        // The render is shown exactly as computed (the pixel readout and a
        // screenshot match the saved PNG), and software rasterizers paint
        // faster without the per-fragment noise.
        dithering: false,
        persist_window: true,
        ..eframe::NativeOptions::default()
    };
    let initial = scene.map(SceneSource::File);
    let outcome = ScreenshotOutcome::default();
    let app_outcome = outcome.clone();
    let plan = screenshot.clone();
    eframe::run_native(
        TITLE,
        options,
        Box::new(move |cc| {
            // The graphics device exists now, and with it the threads of a
            // software rasterizer if there is no GPU.
            platform::paint_priority::lower_software_rasterizer();
            if let Some(render_state) = &cc.wgpu_render_state {
                settle_animations(&cc.egui_ctx, render_state.adapter.get_info().device_type);
            }
            let mut app = WorkbenchApp::new(&cc.egui_ctx, cc.storage, initial);
            app.show_observer(observer);
            if let Some(dir) = &lesson_folder {
                app.open_class(dir);
            }
            if let Some(path) = &lesson {
                app.open_lesson_argument(path);
            }
            Ok(Box::new(match plan {
                Some(plan) => app.with_screenshot(plan, app_outcome),
                None => app,
            }))
        }),
    )
    .map_err(|e| {
        anyhow::anyhow!(
            "cannot open the window: {e}\n(no display? the headless commands still work: \
             see `workbench --help`)"
        )
    })?;
    let Some(plan) = screenshot else {
        return Ok(());
    };
    let taken = outcome.lock().ok().and_then(|mut slot| slot.take());
    match taken {
        Some(Ok(saved)) => {
            println!("{saved}");
            Ok(())
        }
        Some(Err(e)) => Err(anyhow::anyhow!(e)),
        None => anyhow::bail!(
            "the window closed before the screenshot {} was taken",
            plan.path.display()
        ),
    }
}

/// On a software rasterizer (a CPU "device": no GPU) egui animates
/// nothing: each frame there costs the render CPU, and the scroll bars
/// fading in as the panels fill drew more than twice the frames the
/// progress pace asked for during a short first render. Transitions are
/// instant instead. With a GPU, frames are cheap and animations stay.
#[cfg(not(target_family = "wasm"))]
fn settle_animations(ctx: &egui::Context, device: eframe::wgpu::DeviceType) {
    if device == eframe::wgpu::DeviceType::Cpu {
        ctx.all_styles_mut(|style| style.animation_time = 0.0);
    }
}

#[cfg(test)]
mod tests {
    use std::fs;
    use std::path::Path;

    /// The window paints with the patched egui-wgpu of `vendor/` (see its
    /// README): on a software rasterizer its frames cost much less than the
    /// crates.io one's. Fails when the patch stops applying (Cargo ignores a
    /// `[patch]` whose version no longer matches, with a mere warning) or a
    /// new copy of the crate lacks the change.
    #[test]
    fn the_window_paints_with_the_patched_egui_wgpu() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
        let lock = fs::read_to_string(root.join("Cargo.lock")).unwrap();
        let entry = lock
            .split("[[package]]")
            .find(|p| p.contains("\nname = \"egui-wgpu\"\n"))
            .expect("egui-wgpu in Cargo.lock");
        assert!(
            !entry.contains("source ="),
            "egui-wgpu comes from a registry, not vendor/: {entry}"
        );
        let shader = fs::read_to_string(root.join("vendor/egui-wgpu/src/egui.wgsl")).unwrap();
        let renderer = fs::read_to_string(root.join("vendor/egui-wgpu/src/renderer.rs")).unwrap();
        for (uniform, constant) in [
            ("dithering", "DITHERING"),
            (
                "predictable_texture_filtering",
                "PREDICTABLE_TEXTURE_FILTERING",
            ),
        ] {
            assert!(
                !shader.contains(&format!("r_locals.{uniform}")),
                "the fragment shader reads {uniform} from a uniform again"
            );
            assert!(shader.contains(&format!("override {constant}: bool")));
            assert!(renderer.contains(&format!("\"{constant}\"")));
        }
    }

    /// Software rasterizers get instant transitions (dark and light
    /// themes alike), GPUs keep egui's.
    #[test]
    fn animations_settle_on_a_software_rasterizer_only() {
        use super::settle_animations;
        use eframe::wgpu::DeviceType;
        use egui::Theme;
        let animation_times = |device: Option<DeviceType>| {
            let ctx = egui::Context::default();
            if let Some(device) = device {
                settle_animations(&ctx, device);
            }
            [Theme::Dark, Theme::Light].map(|theme| ctx.style_of(theme).animation_time)
        };
        let usual = animation_times(None);
        assert!(usual.iter().all(|&t| t > 0.0));
        assert_eq!(animation_times(Some(DeviceType::Cpu)), [0.0; 2]);
        for gpu in [
            DeviceType::DiscreteGpu,
            DeviceType::IntegratedGpu,
            DeviceType::VirtualGpu,
        ] {
            assert_eq!(animation_times(Some(gpu)), usual, "{gpu:?}");
        }
    }
}
