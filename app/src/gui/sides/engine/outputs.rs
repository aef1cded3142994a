//! What the current job gives back: its image as shown and as linear
//! floats, the per-pixel views, what was built, and a version that says
//! when any of it changed.

use tracer::accel::AccelInfo;
use tracer::render::{Encoding, RenderJob, Snapshot, View, ViewHeatmap};
use tracer::stats::RenderStats;

use super::{Engine, Version};

impl Engine {
    /// A number that changes whenever the image or statistics change,
    /// including when a new job replaces one that reached the same count.
    pub fn version(&self) -> Version {
        (
            self.jobs_started,
            self.job.as_ref().map_or(0, |j| j.version()),
        )
    }

    /// The current image and statistics.
    pub fn snapshot(&self, encoding: Encoding) -> Option<Snapshot> {
        self.job.as_ref().map(|j| j.snapshot(encoding))
    }

    /// The current job's film as linear floats, for "Save as EXR".
    pub fn linear_image(&self) -> Option<image::Rgb32FImage> {
        self.job.as_ref().map(RenderJob::linear_image)
    }

    /// The current image under `view` (the shaded image while the job
    /// does not measure views).
    pub(crate) fn view_snapshot(
        &self,
        view: View,
        heat: &ViewHeatmap,
        encoding: Encoding,
    ) -> Option<Snapshot> {
        self.job
            .as_ref()
            .map(|j| j.view_snapshot(view, heat, encoding))
    }

    /// The value of a scalar view at one pixel, if the job measures views.
    pub fn view_value(&self, view: View, x: u32, y: u32) -> Option<f32> {
        self.job.as_ref()?.view_value(view, x, y)
    }

    /// The current values of a scalar view, if the job measures views.
    pub fn view_values(&self, view: View) -> Option<Vec<Option<f32>>> {
        self.job.as_ref().and_then(|j| j.view_values(view))
    }

    /// The current job's image size and the pixels its adaptive sampling
    /// still refines (row-major); `None` for uniform sampling or no job.
    pub(crate) fn active_pixels(&self) -> Option<([usize; 2], Vec<bool>)> {
        let settings = self.settings.as_ref()?;
        let mask = self.job.as_ref()?.active_pixels()?;
        Some(([settings.width as usize, settings.height as usize], mask))
    }

    /// The current job's statistics.
    pub fn stats(&self) -> Option<RenderStats> {
        self.job.as_ref().map(RenderJob::stats)
    }

    /// What was built for the current job, once built.
    pub(crate) fn accel_info(&self) -> Option<AccelInfo> {
        self.job
            .as_ref()
            .and_then(|j| j.index())
            .map(|i| i.info().clone())
    }
}
