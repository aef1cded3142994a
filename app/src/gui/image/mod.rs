//! The image area: the viewport (fit, zoom, pan, camera gestures), what is
//! drawn over the image (the structure, the pinned pixel's rays, adaptive
//! sampling's active pixels) and the
//! per-pixel views the image can show instead of the render.

pub(crate) mod active_overlay;
pub(crate) mod pixel_views;
pub(crate) mod ray_paths;
pub(crate) mod structure_overlay;
pub(crate) mod viewport;
