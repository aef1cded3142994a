//! Section 2, Whitted ray tracing: the image at each depth, so what local
//! shading, one bounce and the scene's depth each add can be seen, with
//! the rays of each kind each one traced.

use anyhow::Result;

use super::html::{escape, figure, image, table, titled_section};
use super::{Lab, how_measured, ms};
use crate::measure::benchmark::Measurement;

/// Rays of each kind, the columns every per-frame table shares.
pub fn rays_by_kind(m: &Measurement) -> Vec<String> {
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
pub const RAY_HEADERS: [&str; 5] = ["eye", "shadow", "reflection", "refraction", "all rays"];

fn what_it_adds(m: &Measurement, deepest: u32, opaque: bool) -> String {
    match m.case.settings.max_depth {
        0 => "depth 0: local shading (Blinn-Phong, every light) with hard shadows".into(),
        1 => "depth 1: one bounce of mirror reflection and refraction".into(),
        d if opaque => {
            format!("depth {d}, every transmittance set to 0: mirror reflection without refraction")
        }
        d if d == deepest => format!("depth {d}: the scene's depth, with refraction"),
        d => format!("depth {d}"),
    }
}

pub fn section(lab: &Lab) -> Result<String> {
    let deepest = lab.base.max_depth;
    let mut figures = String::new();
    let mut rows = Vec::new();
    // The opaque frame goes just before the scene's depth with refraction.
    let mut frames: Vec<(&Measurement, bool)> = lab.whitted.iter().map(|m| (m, false)).collect();
    if let Some(opaque) = &lab.opaque {
        frames.insert(frames.len().saturating_sub(1), (opaque, true));
    }
    for (m, opaque) in frames {
        let depth = m.case.settings.max_depth;
        let caption = format!(
            "{}; {} ms, {} rays",
            what_it_adds(m, deepest, opaque),
            ms(m.median()),
            m.rays()
        );
        figures += &figure(&image(&m.image, &caption, 340)?, &caption);
        let (name, id) = if opaque {
            (
                format!("depth {depth}, no refraction"),
                format!("depth{depth}-opaque"),
            )
        } else {
            (format!("depth {depth}"), format!("depth{depth}"))
        };
        let mut cells = vec![name, ms(m.median())];
        cells.extend(rays_by_kind(m));
        rows.push((id, cells));
    }
    let mut headers = vec!["image", "frame ms"];
    headers.extend(RAY_HEADERS);
    let body = format!(
        "<p>Whitted's algorithm at increasing depth: each eye ray is shaded locally with a \
         shadow ray to every light, then reflected and refracted rays are traced as deep as \
         allowed. BVH, one sample per pixel, hard shadows. When something refracts, the \
         scene's depth is shown once more with every transmittance set to 0, so what \
         reflection and refraction each add can be told apart.</p>\n\
         <div class=\"figures\">{figures}</div>\n{}\
         <p class=\"how\">{}</p>\n",
        table("whitted", &headers, &rows),
        escape(&how_measured(lab))
    );
    Ok(titled_section("whitted", "2. Whitted ray tracing", &body))
}
