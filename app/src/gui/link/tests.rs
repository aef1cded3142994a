use tracer::accel::AccelKind;
use tracer::render::{RenderSettings, Sampling};

use super::*;

fn bundled(name: &str) -> Option<Source> {
    Some(Source::Bundled(name.into()))
}

fn url(path: &str) -> Option<Source> {
    Some(Source::Url(path.into()))
}

#[test]
fn a_lesson_and_a_scene_are_read_with_or_without_the_question_mark() {
    let both = Link {
        lesson: bundled("shadows"),
        scene: bundled("balls_low"),
        ..Link::default()
    };
    assert_eq!(
        Link::parse("?lesson=shadows&scene=balls_low"),
        Ok(both.clone())
    );
    assert_eq!(Link::parse("scene=balls_low&lesson=shadows"), Ok(both));
    assert_eq!(Link::parse(""), Ok(Link::default()));
    assert_eq!(Link::parse("?"), Ok(Link::default()));
}

#[test]
fn a_value_with_a_slash_or_a_dot_is_a_url_a_bare_word_a_name() {
    let link = Link::parse("?lesson=lessons/mine.toml&scene=my/scene.p3f").unwrap();
    assert_eq!(link.lesson, url("lessons/mine.toml"));
    assert_eq!(link.scene, url("my/scene.p3f"));
    assert_eq!(
        Link::parse("?scene=mine.p3f").unwrap().scene,
        url("mine.p3f")
    );
    assert_eq!(Link::parse("?scene=/x/y").unwrap().scene, url("/x/y"));
    let named = Link::parse("?scene=balls-low_2").unwrap();
    assert_eq!(named.scene, bundled("balls-low_2"));
}

#[test]
fn a_url_to_another_site_is_refused() {
    for query in [
        "?scene=https://example.com/a.p3f",
        "?lesson=//example.com/a.toml",
        "?scene=javascript:alert(1)",
    ] {
        let error = Link::parse(query).unwrap_err();
        assert!(
            error.contains("not on the page's own site"),
            "{query}: {error}"
        );
    }
}

#[test]
fn values_are_percent_decoded() {
    let link = Link::parse("?scene=my%20scene+two%2Ep3f").unwrap();
    assert_eq!(link.scene, url("my scene two.p3f"));
    let link = Link::parse("?lesson=%C3%A9t%C3%A9").unwrap();
    assert_eq!(link.lesson, bundled("été"));
}

#[test]
fn unknown_repeated_empty_and_broken_values_are_refused_by_name() {
    for (query, said) in [
        (
            "?lessons=shadows",
            "the link's `lessons` is not a setting: a link reads lesson, folder, step",
        ),
        ("?lesson=a&lesson=b", "lesson twice"),
        ("?lesson=a&step=1&step=2", "step twice"),
        ("?scene=", "scene is empty"),
        ("?scene", "scene is empty"),
        ("?lesson=%4", "not valid"),
        ("?lesson=%zz", "not valid"),
        ("?lesson=%FF", "not valid"),
        ("?lesson=a&step=0", "not a step number"),
        ("?lesson=a&step=two", "not a step number"),
        ("?step=2", "no lesson"),
        ("?folder=class", "a lessons.index file beside the page"),
        ("?folder=", "folder is empty"),
        (
            "?folder=a/lessons.index&folder=b/lessons.index",
            "folder twice",
        ),
        (
            "?folder=a/lessons.index&lesson=shadows",
            "a folder and a lesson",
        ),
        (
            "?folder=https://example.com/lessons.index",
            "not on the page's own site",
        ),
    ] {
        let error = Link::parse(query).unwrap_err();
        assert!(error.contains(said), "{query}: {error}");
    }
}

#[test]
fn settings_are_the_settings_words_and_their_errors_name_the_word() {
    let link = Link::parse("?scene=balls_low&spp=4&accel=grid&aa&set=object+0+ior+1.5").unwrap();
    let line = link.settings_line().unwrap();
    assert_eq!(line.overrides.spp, Some(4));
    assert_eq!(line.overrides.accel, Some(AccelKind::Grid));
    assert!(line.overrides.aa);
    assert_eq!(line.set, ["object 0 ior 1.5"]);
    for (query, said) in [
        ("?spp=many", "`--spp` takes a whole number, not `many`"),
        ("?spp", "`--spp` needs a value"),
        ("?aa=yes", "`--aa` takes no value"),
        ("?accel=kd", "`--accel` takes none, grid or bvh, not `kd`"),
        ("?fast", "the link's `fast` is not a setting"),
        ("?srgb", "the window shows sRGB always; drop srgb"),
    ] {
        let error = Link::parse(query).unwrap_err();
        assert!(error.contains(said), "{query}: {error}");
    }
}

#[test]
fn a_query_written_reads_back_as_the_same_link() {
    let link = Link {
        lesson: url("lessons/my lesson.toml"),
        folder: None,
        step: Some(3),
        scene: bundled("balls_low"),
        settings: vec![
            ("spp".into(), "4".into()),
            ("aa".into(), String::new()),
            ("set".into(), "object 5 ior 1.33".into()),
            ("set".into(), "material 2 kd 0.5 & more".into()),
        ],
    };
    let query = link.query();
    assert_eq!(
        query,
        "?lesson=lessons/my+lesson.toml&step=3&scene=balls_low&spp=4&aa\
         &set=object+5+ior+1.33&set=material+2+kd+0.5+%26+more"
    );
    assert_eq!(Link::parse(&query), Ok(link));
    assert_eq!(Link::default().query(), "");
}

/// `settings` changed by `change`, its flags applied to it again as a
/// link's settings are: the same settings back.
fn round_trip(change: impl FnOnce(&mut RenderSettings)) -> Vec<(String, String)> {
    let base = RenderSettings::default();
    let mut now = base.clone();
    change(&mut now);
    let flags = settings_flags(&now, &base);
    let link = Link {
        settings: flags.clone(),
        ..Link::default()
    };
    let mut back = base.clone();
    link.settings_line().unwrap().overrides.apply(&mut back);
    assert_eq!(back, now, "{flags:?}");
    flags
}

#[test]
fn the_settings_on_screen_become_flags_that_set_them_again() {
    assert_eq!(round_trip(|_| {}), Vec::<(String, String)>::new());
    let flags = round_trip(|s| s.set_samples(3));
    assert_eq!(flags, [("spp".to_string(), "3".to_string())]);
    round_trip(|s| {
        s.width = 320;
        s.max_depth = 7;
        s.antialiasing = !s.antialiasing;
        s.soft_shadows = true;
        s.light_size = 0.75;
        s.ambient = 0.115;
        s.accel = AccelKind::Grid;
        s.grid_multiplier = 3.5;
        s.seed = 42;
    });
    round_trip(|s| {
        s.set_samples(4);
        s.sample_adaptively(|a| {
            a.noise_threshold = 0.02;
            a.max_spp = 20;
        });
        s.antialiasing = true;
    });
    round_trip(|s| {
        s.shadows = false;
        s.lens_override.aperture = Some(8.0);
        s.depth_of_field = true;
        s.lens_override.focal = Some(1.5);
    });
    let uniform = |s: &mut RenderSettings| {
        s.sampling = Sampling::Uniform;
    };
    let mut adaptive = RenderSettings::default();
    adaptive.sample_adaptively(|_| {});
    assert_eq!(
        settings_flags(
            &{
                let mut s = adaptive.clone();
                uniform(&mut s);
                s
            },
            &adaptive
        ),
        [("sampling".to_string(), "uniform".to_string())]
    );
}

#[test]
fn a_folder_is_its_index_files_url_and_reads_back() {
    let link = Link::parse("?folder=class/lessons.index").unwrap();
    assert_eq!(link.folder.as_deref(), Some("class/lessons.index"));
    assert_eq!(Link::parse(&link.query()), Ok(link));
}

#[test]
fn a_file_is_read_beside_the_url_that_names_it() {
    assert_eq!(
        beside("class/lessons.index", "prism.toml"),
        "class/prism.toml"
    );
    assert_eq!(
        beside("a/b/mine.toml", "../scenes/x.p3f"),
        "a/b/../scenes/x.p3f"
    );
    assert_eq!(beside("lessons.index", "prism.toml"), "prism.toml");
}
