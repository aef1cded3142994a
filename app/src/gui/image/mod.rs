//! The image area: the viewport (fit, zoom, pan, camera gestures), what is
//! drawn over the image (the structure, the pinned pixel's rays, adaptive
//! sampling's active pixels) and the
//! per-pixel views the image can show instead of the render.

pub mod active_overlay;
pub mod pixel_views;
pub mod ray_paths;
pub mod structure_overlay;
pub mod viewport;
