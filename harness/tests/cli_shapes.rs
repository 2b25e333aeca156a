//! `harness simulate` on scene files with the new shapes, through the real
//! binary: a chain, a loop, a concave polygon and a compound run under
//! `--compare rapier,box2d --html` and the replay draws the chains'
//! segments; rounded shapes (segment, capsule, rounded polygon) run under
//! the soft step with `--compare rapier,box2d --html`, and without contacts
//! the comparison says why each adapter does not take the scene. (The adapters' rounded shapes
//! are checked by `references`' unit tests: `rapier_many/tests.rs`,
//! `box2d_world/tests.rs`.)

mod common;
use common::{harness, workspace};

/// The JSON between the replay page's data tags.
fn page_data(html: &str) -> serde_json::Value {
    let start = html.find("type=\"application/json\">").unwrap() + 24;
    let end = start + html[start..].find("</script>").unwrap();
    serde_json::from_str(&html[start..end]).unwrap()
}

#[test]
fn chains_concave_polygons_and_compounds_are_compared_and_replayed() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = workspace().join("scenes/examples/chains_and_pieces.toml");
    let done = harness(
        dir.path(),
        &[
            "simulate",
            scene.to_str().unwrap(),
            "--compare",
            "rapier,box2d",
            "--html",
            "shapes.html",
        ],
    );
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    assert!(!done.stdout.contains("not compared"), "{}", done.stdout);
    for engine in ["rapier2d-f64 0.36.1", "Box2D 3.2 (boxdd 0.6)"] {
        assert!(
            done.stdout
                .contains(&format!("{engine} against the engine")),
            "{}",
            done.stdout
        );
    }
    // The engine says what it made of the concave outline.
    assert!(
        done.stdout.contains("body 'l_piece'") && done.stdout.contains("2 convex parts"),
        "{}",
        done.stdout
    );
    // The ball stays in the clockwise loop (its inside is solid): the
    // ring's floor is at y = 2 m, the ball's radius 0.3 m.
    let ball = done
        .stdout
        .lines()
        .find(|l| l.trim_start().starts_with("ball:"))
        .unwrap();
    let y: f64 = ball
        .split("y = ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((2.0..4.0).contains(&y), "{ball}");
    let html = std::fs::read_to_string(dir.path().join("shapes.html")).unwrap();
    let data = page_data(&html);
    let bodies = data["bodies"].as_array().unwrap();
    let parts = |name: &str| -> Vec<serde_json::Value> {
        bodies.iter().find(|b| b["name"] == name).unwrap()["parts"]
            .as_array()
            .unwrap()
            .clone()
    };
    // The open chain of 6 points has 3 solid segments (its ends are
    // ghosts), the loop of 4 points 4; each drawn as its two ends and back.
    let ground = parts("ground");
    assert_eq!(ground.len(), 3, "{ground:?}");
    let first: Vec<f64> = serde_json::from_value(ground[0]["polygon"].clone()).unwrap();
    assert_eq!(first, vec![5.0, 0.0, 2.0, -0.5, 5.0, 0.0]);
    assert_eq!(parts("ring").len(), 4);
    assert_eq!(parts("hammer").len(), 2);
    assert_eq!(parts("l_piece").len(), 2);
    assert_eq!(data["runs"].as_array().unwrap().len(), 3);
}

#[test]
fn rounded_shapes_under_the_soft_step_are_compared_and_replayed() {
    let dir = tempfile::tempdir().expect("temp dir");
    let text = std::fs::read_to_string(workspace().join("scenes/examples/capsules.toml")).unwrap();
    // The same bodies with contacts on (and no `method`, which the soft
    // step sets itself), without the landing event that ends the flight,
    // for 1.6 s: they land on the segment ground about 1.1 s in and tumble
    // on it.
    let with_contacts: String = text
        .lines()
        .take_while(|l| !l.starts_with("[[events]]"))
        .filter(|l| !l.starts_with("method"))
        .map(|l| {
            if l.starts_with("duration") {
                "duration = 1.6\n".to_string()
            } else {
                format!("{l}\n")
            }
        })
        .collect::<String>()
        + "\n[contact]\n";
    std::fs::write(dir.path().join("capsules.toml"), with_contacts).unwrap();
    let done = harness(
        dir.path(),
        &[
            "simulate",
            "capsules.toml",
            "--compare",
            "rapier,box2d",
            "--html",
            "c.html",
        ],
    );
    assert_eq!(done.code, Some(0), "{}\n{}", done.stdout, done.stderr);
    assert!(!done.stdout.contains("not compared"), "{}", done.stdout);
    for engine in ["rapier2d-f64 0.36.1", "Box2D 3.2 (boxdd 0.6)"] {
        assert!(
            done.stdout
                .contains(&format!("{engine} against the engine")),
            "{}",
            done.stdout
        );
    }
    // Each ends on the ground, not in it: its centre (of mass) at least its
    // least distance to its own outline above y = 0, less the soft step's
    // linear slop, 5 mm, the overlap its contacts leave. That distance is
    // the capsule's radius, 0.25 m; the tile's outer half-height, 0.2 m;
    // for the gem, a triangle of base 0.6 m and height 0.5 m rounded by
    // 0.08 m, its centroid's distance to the base, 0.5/3 m (the slanted
    // sides are 0.1715 m away), plus 0.08 m.
    for (body, lowest) in [("capsule", 0.25), ("tile", 0.2), ("gem", 0.5 / 3.0 + 0.08)] {
        let line = done
            .stdout
            .lines()
            .find(|l| l.trim_start().starts_with(&format!("{body}:")))
            .unwrap();
        let y: f64 = line
            .split("y = ")
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(y > lowest - 0.005, "{line}");
    }
    let data = page_data(&std::fs::read_to_string(dir.path().join("c.html")).unwrap());
    assert_eq!(data["runs"].as_array().unwrap().len(), 3);
}

#[test]
fn rounded_shapes_without_contacts_run_and_each_adapter_says_why_not() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = workspace().join("scenes/examples/capsules.toml");
    // Run alone, the scene draws its capsule, segment and rounded shapes.
    let done = harness(
        dir.path(),
        &["simulate", scene.to_str().unwrap(), "--html", "c.html"],
    );
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    let data = page_data(&std::fs::read_to_string(dir.path().join("c.html")).unwrap());
    let bodies = data["bodies"].as_array().unwrap();
    // The ground segment: its two ends and back.
    let ground: Vec<f64> =
        serde_json::from_value(bodies[0]["parts"][0]["polygon"].clone()).unwrap();
    assert_eq!(ground.len(), 6, "{ground:?}");
    // The capsule: an outline of many chords.
    let capsule = bodies[1]["parts"][0]["polygon"].as_array().unwrap().len();
    assert!(capsule > 40, "{capsule} coordinates");
    // Compared, each adapter names the scene and its reason.
    let done = harness(
        dir.path(),
        &[
            "simulate",
            scene.to_str().unwrap(),
            "--compare",
            "rapier,box2d",
        ],
    );
    assert_eq!(done.code, Some(2), "{}", done.stdout);
    for engine in ["--compare rapier:", "--compare box2d:"] {
        assert!(
            done.stderr.contains(engine) && done.stderr.contains("capsules.toml"),
            "{}",
            done.stderr
        );
    }
}
