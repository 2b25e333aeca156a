use super::*;
use crate::progress::Ticker;
use crate::simulate::{RunLimits, record};

fn scene(text: &str) -> Scene {
    Scene::parse_str("inline.toml", text).unwrap()
}

fn replay_of(scene: &Scene) -> Replay {
    let mut world = scene.build_world(None).unwrap();
    let rec = record(
        &mut world,
        scene.duration(),
        scene.dt(),
        &RunLimits::default(),
        Ticker::new(indicatif::ProgressBar::hidden(), 1),
        |_, _, _| {},
    )
    .unwrap();
    let mut replay = Replay::new(
        scene,
        world.bodies(),
        "inline.toml".into(),
        "rk4".into(),
        scene.dt(),
    );
    replay.runs.push(ReplayRun {
        label: "this engine (rk4)".into(),
        short: "engine".into(),
        times: rec.samples.times,
        states: rec.samples.states,
        energies: Some(rec.samples.energies),
        events: ReplayEvent::from_records(scene, &rec.run.events),
    });
    replay
}

/// The JSON between the data element's tags, read back.
fn data_of(html: &str) -> serde_json::Value {
    let start = html.find("type=\"application/json\">").unwrap() + 24;
    let end = start + html[start..].find("</script>").unwrap();
    serde_json::from_str(&html[start..end]).unwrap()
}

const BALL: &str = "[simulation]\nmethod = \"rk4\"\ndt = 0.01\nduration = 1.0\n\
    [[bodies]]\nname = \"ground\"\nkind = \"static\"\nshape = { type = \"box\", width = 20.0, height = 1.0 }\nposition = [0.0, -0.5]\n\
    [[bodies]]\nname = \"ball\"\nmass = 1.0\nshape = { type = \"circle\", radius = 0.1 }\nposition = [0.0, 1.1]\nvelocity = [1.0, 0.0]\n\
    [[forces]]\ntype = \"gravity\"\ng = [0.0, -9.81]\n";

#[test]
fn a_page_is_self_contained_and_its_data_reads_back() {
    let scene = scene(BALL);
    let mut replay = replay_of(&scene);
    let page = replay.page().unwrap();
    let html = &page.html;
    assert!(html.starts_with("<!DOCTYPE html>"));
    // No template placeholder left, nothing fetched from elsewhere.
    for absent in [
        "{{", "/*{{", "http://", "https://", "src=", "@import", "url(",
    ] {
        assert!(!html.contains(absent), "the page holds {absent:?}");
    }
    let data = data_of(html);
    assert_eq!(data["version"], 2);
    let bodies = data["bodies"].as_array().unwrap();
    assert_eq!(bodies[0]["name"], "ground");
    // A static body without a colour of its own is grey; the ball, the
    // first moving body, takes the palette's first colour (tab10's blue:
    // moving bodies are counted alone, so the ground shifts nothing).
    assert_eq!(bodies[0]["colour"], STATIC_GREY.to_string());
    assert_eq!(bodies[1]["colour"], "#1f77b4");
    assert_eq!(bodies[1]["parts"][0]["circle"][2], 0.1);
    let run = &data["runs"][0];
    assert!(
        run["bodies"][0]["fixed"].is_array(),
        "the ground is stored once"
    );
    // A parabola: thinned, yet every sample within the tolerance.
    let frames = page.frames[0];
    assert!(frames > 3 && frames < 101, "{frames} frames");
    let q = run["q"]["p"].as_f64().unwrap();
    let ys: Vec<i64> = serde_json::from_value(run["bodies"][1]["y"].clone()).unwrap();
    assert_eq!(ys.len(), frames);
    assert!((ys[0] as f64 * q - 1.1).abs() <= q / 2.0);
}

#[test]
fn the_view_holds_the_motion_and_only_the_near_part_of_a_wide_floor() {
    let scene = scene(BALL);
    let mut replay = replay_of(&scene);
    replay.page().unwrap();
    let (lo, hi) = replay.view;
    // The ball goes from x = 0 to 1 m and falls from 1.1 m to ~-3.8 m
    // (through the floor: contacts are off); the 20 m floor is cut.
    assert!(lo.x <= -0.1 && hi.x >= 1.1, "{lo} {hi}");
    assert!(hi.x - lo.x < 12.0, "{lo} {hi}");
    assert!(hi.y >= 1.2 && lo.y <= -3.7, "{lo} {hi}");
}

#[test]
fn a_name_cannot_close_the_data_element() {
    let text = BALL.replace("name = \"ball\"", "name = \"</script><b>\"");
    let scene = scene(&text);
    let mut replay = replay_of(&scene);
    let html = replay.page().unwrap().html;
    assert_eq!(html.matches("</script>").count(), 2, "data and script only");
    assert_eq!(data_of(&html)["bodies"][1]["name"], "</script><b>");
}

#[test]
fn a_page_of_many_particles_keeps_its_bound_and_states_it() {
    // 400 particles falling side by side for 2 s: every one moves. The page
    // is never coarsened to fit a size: with no shaped body its bound is
    // 1/2000 of the view, what it shows stays within it, and it says so.
    let mut text = String::from("[simulation]\nmethod = \"rk4\"\ndt = 0.01\nduration = 2.0\n");
    for i in 0..400 {
        text.push_str(&format!(
            "[[bodies]]\nname = \"p{i}\"\nmass = 1.0\nposition = [{}, 0.0]\nvelocity = [0.0, {}]\n",
            i as f64 * 0.1,
            (i % 7) as f64
        ));
    }
    text.push_str("[[forces]]\ntype = \"gravity\"\ng = [0.0, -9.81]\n");
    let scene = scene(&text);
    let mut replay = replay_of(&scene);
    let page = replay.page().unwrap();
    assert_eq!(page.smallest_width, None);
    assert!((page.tolerance - VIEW_SHARE * replay.view_size()).abs() < 1e-15);
    assert!(page.max_error <= page.tolerance, "{page:?}");
    // A parabola sampled every 10 ms over 2 s: thinned, not kept whole.
    assert!(
        page.frames[0] >= 3 && page.frames[0] < 201,
        "{:?}",
        page.frames
    );
    let data = data_of(&page.html);
    let notes = data["notes"].as_array().unwrap();
    assert!(
        notes
            .iter()
            .any(|n| n.as_str().unwrap().contains("B of data."))
    );
}

#[test]
fn the_bound_is_a_hundredth_of_the_smallest_moving_body() {
    // The ball of radius 0.1 m: its width 0.2 m, the bound 2 mm; the
    // 20 m static floor does not count.
    let scene = scene(BALL);
    let mut replay = replay_of(&scene);
    let page = replay.page().unwrap();
    assert_eq!(page.smallest_width, Some(0.2));
    assert!((page.tolerance - 0.002).abs() < 1e-15);
    assert!(page.max_error <= page.tolerance);
    let html = &page.html;
    let data = data_of(html);
    let notes = data["notes"].to_string();
    assert!(
        notes.contains("within 0.002000 m of every sample"),
        "{notes}"
    );
}

#[test]
fn principal_angles_are_unwrapped() {
    let turn = |a: f64| BodyState {
        angle: a,
        ..BodyState::default()
    };
    let mut states = vec![vec![turn(3.0)], vec![turn(-3.0)], vec![turn(-2.0)]];
    unwrap_angles(&mut states);
    let tau = std::f64::consts::TAU;
    assert!((states[1][0].angle - (tau - 3.0)).abs() < 1e-12);
    assert!((states[2][0].angle - (tau - 2.0)).abs() < 1e-12);
}
