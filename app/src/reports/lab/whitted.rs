//! Section 2, Whitted ray tracing: local shading only, then hard shadows,
//! one bounce and the scene's depth, so what each part adds can be seen,
//! with the rays of each kind each one traced.

use anyhow::Result;

use super::html::{escape, figure, image, table, titled_section};
use super::{Lab, how_measured, ms};
use crate::measure::benchmark::Measurement;

/// Rays of each kind, the columns every per-frame table shares.
pub(crate) fn rays_by_kind(m: &Measurement) -> Vec<String> {
    let c = &m.stats.counters;
    [
        c.eye_rays,
        c.shadow_rays,
        c.reflection_rays,
        c.refraction_rays,
        c.total_rays(),
    ]
    .iter()
    .map(u64::to_string)
    .collect()
}

/// Headers of [`rays_by_kind`].
pub(crate) const RAY_HEADERS: [&str; 5] = ["eye", "shadow", "reflection", "refraction", "all rays"];

/// A frame of the section: what its settings add to the one before, in
/// words, and its row's name and id.
struct WhittedFrame {
    adds: String,
    name: String,
    id: String,
}

/// `opaque`: the frame of the scene with every transmittance set to 0;
/// `refracts`: whether anything in the scene transmits.
fn step(m: &Measurement, deepest: u32, opaque: bool, refracts: bool) -> WhittedFrame {
    let depth = m.case.settings.max_depth;
    let (name, id) = (format!("depth {depth}"), format!("depth{depth}"));
    let said = |adds: String, name: String, id: String| WhittedFrame { adds, name, id };
    if !m.case.settings.shadows {
        return said(
            "local shading only: Blinn-Phong from every light the surface faces, no shadow \
             rays, no bounce"
                .into(),
            "local shading".into(),
            "local".into(),
        );
    }
    let refraction = if refracts { " and refraction" } else { "" };
    match depth {
        0 => said(
            "depth 0: with hard shadows, a shadow ray to every light".into(),
            name,
            id,
        ),
        1 => said(
            format!("depth 1: one bounce of reflection{refraction}"),
            name,
            id,
        ),
        d if opaque => said(
            format!("depth {d}, every transmittance set to 0: reflection without refraction"),
            format!("{name}, no refraction"),
            format!("{id}-opaque"),
        ),
        d if d == deepest && refracts => said(
            format!("depth {d}: the scene's depth, with refraction"),
            name,
            id,
        ),
        d if d == deepest => said(
            format!("depth {d}: the scene's depth (nothing in it refracts)"),
            name,
            id,
        ),
        d => said(format!("depth {d}"), name, id),
    }
}

pub(crate) fn section(lab: &Lab) -> Result<String> {
    let deepest = lab.base.max_depth;
    let mut figures = String::new();
    let mut rows = Vec::new();
    // The opaque frame goes just before the scene's depth with refraction.
    let mut frames: Vec<(&Measurement, bool)> = lab.whitted.iter().map(|m| (m, false)).collect();
    if let Some(opaque) = &lab.opaque {
        frames.insert(frames.len().saturating_sub(1), (opaque, true));
    }
    let refracts = lab.opaque.is_some();
    for (m, opaque) in frames {
        let WhittedFrame { adds, name, id } = step(m, deepest, opaque, refracts);
        let caption = format!("{adds}; {} ms, {} rays", ms(m.median()), m.rays());
        figures += &figure(&image(&m.image, &caption, 340)?, &caption);
        let mut cells = vec![name, ms(m.median())];
        cells.extend(rays_by_kind(m));
        rows.push((id, cells));
    }
    let mut headers = vec!["image", "frame ms"];
    headers.extend(RAY_HEADERS);
    let body = format!(
        "<p>Whitted's algorithm one part at a time: each eye ray's hit shaded locally from \
         every light it faces (no shadow rays), then with a shadow ray to every light (hard \
         shadows), then reflected and refracted rays traced as deep as allowed. BVH, one \
         sample per pixel. When something refracts, the scene's depth is shown once more \
         with every transmittance set to 0, so what reflection and refraction each add can be \
         told apart.</p>\n\
         <div class=\"figures\">{figures}</div>\n{}\
         <p class=\"how\">{}</p>\n",
        table("whitted", &headers, &rows),
        escape(&how_measured(lab))
    );
    Ok(titled_section("whitted", "2. Whitted ray tracing", &body))
}
