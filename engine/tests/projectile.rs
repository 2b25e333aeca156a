//! The seed's projectile (docs/cases.md case II `projectile` and
//! `projectile_drag`, seed §6): a 0.1 m × 0.1 m, 0.3 kg box launched from
//! the origin at 60 m/s, 45°, under g = 9.80655 m/s² (the seed's value;
//! standard gravity is 9.80665), dt = 0.01 s, with the landing (y = 0,
//! terminal) and apex (vy = 0) events located inside the step.

use etalon2d::forces::{Gravity, QuadraticDrag};
use etalon2d::{BodyDef, EventSpec, Method, Shape, Tolerance, Trace, World};
use nalgebra::Vector2;

const G: f64 = 9.80655;
const V0: f64 = 60.0;
const DT: f64 = 0.01;

fn launch_velocity() -> Vector2<f64> {
    let alpha = std::f64::consts::FRAC_PI_4;
    Vector2::new(V0 * alpha.cos(), V0 * alpha.sin())
}

/// The seed box, with or without quadratic drag D = 0.003 kg/m, run by
/// `method` at step `dt` until landing (or 8.7 s).
fn run(method: Method, dt: f64, drag: bool) -> (World, Trace) {
    let mut world = World::new(method).unwrap();
    let shape = Shape::rectangle(0.1, 0.1).unwrap();
    let id = world
        .add_body(BodyDef::rigid("box", 0.3, shape).with_velocity(launch_velocity()))
        .unwrap();
    assert_eq!(id, 0);
    world
        .add_force(Gravity {
            g: Vector2::new(0.0, -G),
        })
        .unwrap();
    if drag {
        world
            .add_force(QuadraticDrag {
                body: id,
                coefficient: 0.003,
            })
            .unwrap();
    }
    world.add_event(EventSpec::landing(id, 0.0)).unwrap();
    world.add_event(EventSpec::apex(id)).unwrap();
    let trace = world.run(8.7, dt).unwrap();
    (world, trace)
}

fn parabola(t: f64) -> Vector2<f64> {
    let v = launch_velocity();
    Vector2::new(v.x * t, v.y * t - 0.5 * G * t * t)
}

fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

#[test]
fn seed_box_mass_properties_come_from_the_geometry() {
    let (world, _) = run(Method::Rk4, DT, false);
    let body = &world.bodies()[0];
    assert_eq!(body.mass, 0.3);
    // I = m(b² + h²)/12 = 5e-4 kg·m²; the polygon sum rounds: a few ulps
    // (ulp(5e-4) ≈ 1.1e-19).
    let inertia = body.inertia.expect("a box rotates");
    assert!((inertia - 5e-4).abs() < 1e-18, "I = {inertia:e}");
}

#[test]
fn rk2_rk4_and_verlet_are_exact_on_the_parabola() {
    for method in [Method::Midpoint, Method::Rk4, Method::VelocityVerlet] {
        let (_, trace) = run(method, DT, false);
        // A quadratic in t is integrated exactly by these methods: only
        // round-off remains (≈ 865 steps × ulp(367 m) ≈ 5e-11 m). docs/cases.md:
        // "< 1e-9 m".
        for s in &trace.samples {
            let err = (s.states[0].position - parabola(s.t)).norm();
            assert!(err < 1e-9, "{} t = {}: error {err:e} m", method.id(), s.t);
        }
        // Events on an exact trajectory sit at the closed-form times:
        // T = 2 vy0/g, R = vx0 T, H = vy0²/(2g) at vy0/g. The root finder
        // closes to 1e-15 of the time: 1e-12 relative is round-off.
        let v = launch_velocity();
        let landing = trace.event("landing").expect("it lands");
        let apex = trace.event("apex").expect("it peaks");
        assert!(rel(landing.t, 2.0 * v.y / G) < 1e-12, "{}", method.id());
        assert!(rel(landing.states[0].position.x, v.x * 2.0 * v.y / G) < 1e-12);
        assert!(landing.states[0].position.y.abs() < 1e-9, "lands on y = 0");
        assert!(rel(apex.t, v.y / G) < 1e-12, "{}", method.id());
        assert!(rel(apex.states[0].position.y, v.y * v.y / (2.0 * G)) < 1e-12);
        // The terminal event ends the run at its exact time.
        assert_eq!(trace.last().unwrap().t, landing.t);
    }
}

#[test]
fn rk4_landing_matches_the_cases_md_digits() {
    let (world, trace) = run(Method::Rk4, DT, false);
    let landing = trace.event("landing").unwrap();
    let apex = trace.event("apex").unwrap();
    // docs/cases.md quotes 10 significant digits (rounding ≤ 6e-11 relative);
    // 1e-9 relative leaves room for that and nothing more than round-off.
    assert!(rel(landing.t, 8.652667222) < 1e-9, "T = {}", landing.t);
    let range = landing.states[0].position.x;
    assert!(rel(range, 367.1015801) < 1e-9, "R = {range}");
    let height = apex.states[0].position.y;
    assert!(rel(height, 91.77539502) < 1e-9, "H = {height}");
    assert!(rel(apex.t, 4.326333611) < 1e-9, "t_H = {}", apex.t);
    assert!(world.is_stopped(), "landing is terminal");
    assert_eq!(world.time(), landing.t);
    let events: Vec<&str> = trace.events.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(events, ["apex", "landing"], "in time order, once each");
}

#[test]
fn euler_methods_err_by_plus_or_minus_g_h_t_over_2() {
    // Explicit Euler: y_n = vy0 t_n − g h² n(n−1)/2 = y(t_n) + g h t_n/2.
    // Semi-implicit: y_n = vy0 t_n − g h² n(n+1)/2 = y(t_n) − g h t_n/2.
    // x is exact for both (vx is constant).
    for (method, sign) in [
        (Method::ExplicitEuler, 1.0),
        (Method::SemiImplicitEuler, -1.0),
    ] {
        let (_, trace) = run(method, DT, false);
        // The last sample is the landing, inside a step: not a grid time.
        let grid = &trace.samples[1..trace.samples.len() - 1];
        assert!(
            grid.len() > 800,
            "{}: {} grid samples",
            method.id(),
            grid.len()
        );
        for s in grid {
            let expected = sign * G * DT * s.t / 2.0;
            let err = s.states[0].position - parabola(s.t);
            // Round-off ≈ 1e-13 m against errors ≥ 5e-4 m: 1e-9 relative.
            assert!(
                rel(err.y, expected) < 1e-9,
                "{} t = {}: {} vs {expected}",
                method.id(),
                s.t,
                err.y
            );
            assert!(err.x.abs() < 1e-9, "{} t = {}", method.id(), s.t);
        }
        // At the grid time t = 5 s (sample 500), ±g h t/2 = ±0.2451637 m.
        let s = &trace.samples[500];
        assert_eq!(s.t, 5.0);
        let err_y = s.states[0].position.y - parabola(5.0).y;
        assert!(rel(err_y, sign * 0.245163750) < 1e-9, "{err_y}");
    }
}

#[test]
fn dormand_prince_drag_matches_the_high_precision_reference() {
    // With drag there is no closed form; docs/cases.md quotes a 40-digit Taylor
    // solve to 13 significant digits. DP at 1e-12 (output every 0.1 s, its
    // own steps inside) lands within 1e-9 relative: the tolerance allows
    // ~1e-12 per step over a few hundred steps, far inside 1e-9.
    let method = Method::DormandPrince(Tolerance::uniform(1e-12));
    let (_, trace) = run(method, 0.1, true);
    let landing = trace.event("landing").unwrap();
    let apex = trace.event("apex").unwrap();
    let checks = [
        ("landing T", landing.t, 5.854653263330),
        ("range R", landing.states[0].position.x, 113.8638433141),
        ("impact vx", landing.states[0].velocity.x, 9.559095582234),
        ("impact vy", landing.states[0].velocity.y, -23.01932191094),
        ("apex H", apex.states[0].position.y, 43.00523490712),
        ("apex t", apex.t, 2.570518887719),
        ("apex x", apex.states[0].position.x, 68.34176280439),
    ];
    for (what, got, expected) in checks {
        assert!(rel(got, expected) < 1e-9, "{what}: {got} vs {expected}");
    }
    let s = trace.samples.iter().find(|s| s.t == 5.0).unwrap();
    let st = s.states[0];
    for (what, got, expected) in [
        ("x(5)", st.position.x, 104.7938286099),
        ("y(5)", st.position.y, 18.00633836691),
        ("vx(5)", st.velocity.x, 11.69691072171),
        ("vy(5)", st.velocity.y, -18.89837502420),
    ] {
        assert!(rel(got, expected) < 1e-9, "{what}: {got} vs {expected}");
    }
}

#[test]
fn rk4_with_drag_at_h_0_2_errs_by_4_5e_4_m_at_5_s() {
    let (_, trace) = run(Method::Rk4, 0.2, true);
    let s = trace.samples.iter().find(|s| s.t == 5.0).unwrap();
    let reference = Vector2::new(104.7938286099, 18.00633836691);
    let err = (s.states[0].position - reference).norm();
    // docs/cases.md: "4.5e-4 m", two significant digits: ±0.05e-4.
    assert!((err - 4.5e-4).abs() < 0.05e-4, "error {err:e} m");
}
