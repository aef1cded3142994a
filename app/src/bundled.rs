//! The scenes, lessons and skybox embedded in the binary (see `build.rs`).

/// A scene file compiled into the binary.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BundledScene {
    /// File stem, e.g. `balls_medium`.
    pub(crate) name: &'static str,
    /// File name, e.g. `balls_medium.p3f`.
    pub(crate) file: &'static str,
    /// The file's first comment line.
    pub(crate) description: &'static str,
    pub text: &'static str,
}

/// A scene of `scenes/` the binary does not embed (the web page's, whose
/// download would otherwise be mostly scenes): a file beside the page,
/// fetched when picked. The build lists them, so the page's scene list
/// offers every scene without asking its site for a list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SiteScene {
    /// File stem, e.g. `tetra`.
    pub(crate) name: &'static str,
    /// File name, e.g. `tetra.p3f`.
    pub(crate) file: &'static str,
    /// The file's first comment line.
    pub(crate) description: &'static str,
    /// The file's size in bytes, for the scene list.
    pub(crate) size: u64,
}

impl SiteScene {
    /// Where the page fetches it: `scenes/FILE`, relative to the page.
    pub(crate) fn url(&self) -> String {
        format!("scenes/{}", self.file)
    }
}

/// A lesson file compiled into the binary (see [`crate::lessons`]).
#[derive(Debug, Clone, Copy)]
pub struct BundledLesson {
    /// File stem, e.g. `camera`: the name `workbench lesson check` takes.
    pub(crate) name: &'static str,
    pub(crate) text: &'static str,
}

include!(concat!(env!("OUT_DIR"), "/bundled.rs"));

/// The scene the window opens when it has none to restore.
pub(crate) const DEFAULT_SCENE: &str = "showcase";

/// A bundled scene by name.
pub fn find(name: &str) -> Option<&'static BundledScene> {
    SCENES.iter().find(|s| s.name == name)
}

/// A scene of `scenes/` the binary does not embed, by name.
pub(crate) fn site_scene(name: &str) -> Option<&'static SiteScene> {
    SITE_SCENES.iter().find(|s| s.name == name)
}

/// The site scene fetched from `url` ([`SiteScene::url`]), if any.
pub(crate) fn site_scene_at(url: &str) -> Option<&'static SiteScene> {
    SITE_SCENES.iter().find(|s| s.url() == url)
}

/// A scene the scene list offers: embedded, or a file beside the page.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Offered {
    Embedded(&'static BundledScene),
    Site(&'static SiteScene),
}

impl Offered {
    pub(crate) fn name(&self) -> &'static str {
        match self {
            Offered::Embedded(scene) => scene.name,
            Offered::Site(scene) => scene.name,
        }
    }
}

/// Every scene of `scenes/`, embedded or beside the page, by name: what
/// the scene list offers and a link may name.
pub(crate) fn offered() -> Vec<Offered> {
    offered_of(SCENES, SITE_SCENES)
}

/// `embedded` and `site` scenes in one list sorted by name; a site scene
/// named as an embedded one is the embedded one's file, left out.
fn offered_of(embedded: &'static [BundledScene], site: &'static [SiteScene]) -> Vec<Offered> {
    let mut offered: Vec<Offered> = embedded.iter().map(Offered::Embedded).collect();
    let embedded_names = |name: &str| embedded.iter().any(|e| e.name == name);
    offered.extend(
        site.iter()
            .filter(|s| !embedded_names(s.name))
            .map(Offered::Site),
    );
    offered.sort_by_key(Offered::name);
    offered
}

#[cfg(test)]
mod tests {
    use super::*;

    const fn embedded(name: &'static str) -> BundledScene {
        BundledScene {
            name,
            file: "",
            description: "",
            text: "",
        }
    }

    const fn site(name: &'static str) -> SiteScene {
        SiteScene {
            name,
            file: "",
            description: "",
            size: 1,
        }
    }

    static EMBEDDED: [BundledScene; 2] = [embedded("dof"), embedded("showcase")];
    static SITE: [SiteScene; 3] = [site("balls_low"), site("showcase"), site("tetra")];

    #[test]
    fn embedded_and_site_scenes_are_one_list_by_name() {
        let names: Vec<_> = offered_of(&EMBEDDED, &SITE)
            .iter()
            .map(Offered::name)
            .collect();
        assert_eq!(names, ["balls_low", "dof", "showcase", "tetra"]);
    }

    #[test]
    fn an_embedded_scene_is_offered_as_embedded_not_fetched() {
        let offered = offered_of(&EMBEDDED, &SITE);
        let showcase = offered.iter().find(|o| o.name() == "showcase").unwrap();
        assert_eq!(*showcase, Offered::Embedded(&EMBEDDED[1]));
        assert_eq!(offered.len(), 4);
    }

    #[test]
    fn a_site_scene_is_fetched_beside_the_page() {
        let tetra = SiteScene {
            file: "tetra.p3f",
            ..site("tetra")
        };
        assert_eq!(tetra.url(), "scenes/tetra.p3f");
    }

    #[test]
    fn the_desktop_embeds_every_scene() {
        assert!(SITE_SCENES.is_empty(), "{SITE_SCENES:?}");
        assert_eq!(offered().len(), SCENES.len());
    }
}
