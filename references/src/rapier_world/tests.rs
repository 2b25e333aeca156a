use super::*;
use crate::{DragReference, Projectile, SEED_GRAVITY, SpringOscillator, TorquePulse};

/// The seed box (0.3 kg, 0.1 m × 0.1 m, I = 5e-4 kg·m²) at the origin.
fn seed_box(velocity: [f64; 2]) -> RapierBody {
    RapierBody {
        mass: 0.3,
        inertia: Some(5e-4),
        position: [0.0, 0.0],
        angle: 0.0,
        velocity,
        angular_velocity: 0.0,
    }
}

fn gravity() -> RapierForce {
    RapierForce::Gravity([0.0, -SEED_GRAVITY])
}

#[test]
fn rapier_body_has_exactly_the_requested_mass_and_inertia() {
    let settings = RapierSettings::new(0.01);
    let body = seed_box([1.0, 2.0]);
    let mut sim = SingleBodyWorld::new(&body, &[], &settings);
    sim.world.step();
    let rb = &sim.world.bodies[sim.handle];
    assert!(close(rb.mass(), 0.3), "mass {}", rb.mass());
    let local = rb.mass_properties().local_mprops;
    assert!(close(local.principal_inertia(), 5e-4));
    assert_eq!(local.local_com, Vector::ZERO);
    let (m, i) = sim.mass_properties();
    assert!(close(m, 0.3) && close(i, 5e-4), "{m} {i}");
    assert!(rb.colliders().is_empty());
    assert!(rb.is_fast_rotation_allowed());
    assert_eq!(rb.linear_damping(), 0.0);
    assert_eq!(rb.angular_damping(), 0.0);

    // A particle: rotations locked, effective inverse inertia zero.
    let particle = RapierBody {
        inertia: None,
        angular_velocity: 3.0,
        ..body
    };
    let mut sim = SingleBodyWorld::new(&particle, &[], &settings);
    sim.world.step();
    let (m, i) = sim.mass_properties();
    assert!(close(m, 0.3) && i == 0.0, "{m} {i}");
    let samples = run_single_body(
        &particle,
        &[RapierForce::Torque {
            torque: 1.0,
            start: 0.0,
            end: 1.0,
        }],
        &settings,
        0.1,
    )
    .unwrap();
    assert!(
        samples
            .iter()
            .all(|s| s.angle == 0.0 && s.angular_velocity == 0.0)
    );
}

#[test]
fn rapier_parameters_differ_from_defaults_as_documented() {
    let p = integration_parameters(&RapierSettings {
        dt: 0.2,
        substeps: 3,
    });
    let d = IntegrationParameters::default();
    assert_eq!(p.dt, 0.2);
    assert_eq!(p.num_solver_iterations, 3);
    assert_eq!(p.max_linear_velocity(), f64::MAX);
    assert!(!p.contact_recycling);
    assert_eq!(
        IntegrationParameters {
            dt: d.dt,
            num_solver_iterations: d.num_solver_iterations,
            normalized_max_linear_velocity: d.normalized_max_linear_velocity,
            contact_recycling: d.contact_recycling,
            ..p
        },
        d
    );
    assert_eq!(d.normalized_max_linear_velocity, 400.0);
    assert!(d.contact_recycling);
    let summary = configuration_summary(&RapierSettings::new(0.01));
    for name in [
        "num_solver_iterations",
        "normalized_max_linear_velocity",
        "contact_recycling",
        "can_sleep",
        "allow_fast_rotation",
        "additional_mass_properties",
    ] {
        assert!(summary.contains(name), "{name}");
    }
}

#[test]
fn rapier_rejects_bad_input() {
    let settings = RapierSettings::new(0.01);
    let body = seed_box([0.0, 0.0]);
    let bad_mass = RapierBody { mass: 0.0, ..body };
    assert!(matches!(
        run_single_body(&bad_mass, &[], &settings, 1.0),
        Err(RapierError::InvalidParameter { what: "mass", .. })
    ));
    assert!(matches!(
        run_single_body(&body, &[], &RapierSettings::new(f64::NAN), 1.0),
        Err(RapierError::InvalidParameter { what: "dt", .. })
    ));
    assert!(matches!(
        run_single_body(&body, &[], &settings, 0.005),
        Err(RapierError::DurationNotWholeSteps { .. })
    ));
    let zero_axis = RapierForce::AxialSpring {
        anchor: [0.0, 0.0],
        axis: [0.0, 0.0],
        stiffness: 1.0,
        rest_length: 1.0,
    };
    assert!(run_single_body(&body, &[zero_axis], &settings, 1.0).is_err());
    // A force that overflows: reported, not hidden by rapier's quarantine.
    let huge = RapierForce::AxialSpring {
        anchor: [0.0, 0.0],
        axis: [1.0, 0.0],
        stiffness: 1e300,
        rest_length: -1e300,
    };
    assert!(matches!(
        run_single_body(&body, &[huge], &settings, 1.0),
        Err(RapierError::NonFinite { .. })
    ));
}

/// Vacuum projectile (`docs/cases.md` case II `projectile`), dt = 0.01 s, 4
/// substeps. Symplectic Euler with substep h = dt/s on a constant
/// acceleration g: v_k = v0 + k·g·h, x_N = x0 + h·Σ_{k=1..N} v_k
/// = x0 + v0·t + g·h²·N(N+1)/2 = x0 + v0·t + g·t²/2 + g·h·t/2 (t = N·h).
/// So x is exact, v is exact, and y errs by g_y·h·t/2 = −|g|·h·t/2:
/// −9.80655 × 0.0025 × 8 / 2 = −0.0980655 m at t = 8 s. The tolerance is
/// round-off: 3200 substeps of additions to values ≲ 400 m.
#[test]
fn rapier_vacuum_projectile_errs_by_symplectic_euler_half_substep() {
    let exact = Projectile::seed();
    for substeps in [1, 4] {
        let settings = RapierSettings { dt: 0.01, substeps };
        let body = seed_box(exact.initial_velocity());
        let samples = run_single_body(&body, &[gravity()], &settings, 8.0).unwrap();
        let last = samples.last().unwrap();
        assert_eq!(samples.len(), 801);
        assert_eq!(last.t, 8.0);
        let h = settings.dt / substeps as f64;
        let predicted_dy = -SEED_GRAVITY * h * last.t / 2.0;
        let p = exact.position(last.t);
        let v = exact.velocity(last.t);
        let (ex, ey) = (last.position[0] - p[0], last.position[1] - p[1]);
        eprintln!(
            "rapier projectile, dt 0.01, {substeps} substeps, t = 8 s: x error {ex:.3e} m, \
             y error {ey:.9e} m (predicted -g·h·t/2 = {predicted_dy:.9e} m), \
             v error ({:.2e}, {:.2e}) m/s",
            last.velocity[0] - v[0],
            last.velocity[1] - v[1],
        );
        assert!(ex.abs() < 1e-9, "{ex}");
        assert!((ey - predicted_dy).abs() < 1e-9, "{ey} vs {predicted_dy}");
        assert!((last.velocity[0] - v[0]).abs() < 1e-10);
        assert!((last.velocity[1] - v[1]).abs() < 1e-10);
        assert_eq!(last.angle, 0.0);
    }
}

/// Rapier's one-step map for a force held over s substeps (module docs):
/// x' = x + v·dt + a·dt²·(s+1)/(2s), v' = v + a·dt.
fn held_force_recurrence(
    osc: &SpringOscillator,
    dt: f64,
    substeps: usize,
    steps: usize,
) -> (f64, f64) {
    let c = (substeps as f64 + 1.0) / (2.0 * substeps as f64);
    let (mut x, mut v) = (osc.x0, osc.v0);
    for _ in 0..steps {
        let a = -osc.stiffness * (x - osc.rest_length) / osc.mass;
        x += v * dt + a * dt * dt * c;
        v += a * dt;
    }
    (x, v)
}

fn spring_scene(osc: &SpringOscillator) -> (RapierBody, [RapierForce; 1]) {
    (
        RapierBody {
            mass: osc.mass,
            inertia: None,
            position: [osc.x0, 0.0],
            angle: 0.0,
            velocity: [osc.v0, 0.0],
            angular_velocity: 0.0,
        },
        [RapierForce::AxialSpring {
            anchor: [0.0, 0.0],
            axis: [1.0, 0.0],
            stiffness: osc.stiffness,
            rest_length: osc.rest_length,
        }],
    )
}

/// Mass-spring (`docs/cases.md` case I) at dt = 0.2 s to t = 57.2 s (286
/// steps). The spring force is evaluated once per step and rapier holds it
/// over the substeps, so the step map is the recurrence above; its
/// determinant 1 + (s−1)/(2s)·(ωdt)² is 1.0375 for s = 4 and (ωdt)² = 0.1:
/// the amplitude grows by ≈ 1.0375^(286/2) ≈ 193. With s = 1 it is
/// semi-implicit Euler, bounded, with the energy band of `docs/cases.md`.
#[test]
fn rapier_spring_grows_with_substeps_and_matches_held_force_recurrence() {
    let osc = SpringOscillator::seed();
    let omega = osc.omega();
    let (body, forces) = spring_scene(&osc);
    let steps = 286;
    for substeps in [4, 1] {
        let settings = RapierSettings { dt: 0.2, substeps };
        let samples = run_single_body(&body, &forces, &settings, 57.2).unwrap();
        let last = samples.last().unwrap();
        assert_eq!(samples.len(), steps + 1);
        let (xp, vp) = held_force_recurrence(&osc, 0.2, substeps, steps);
        let scale = xp.abs().max(vp.abs() / omega).max(osc.amplitude());
        assert!(
            (last.position[0] - xp).abs() < 1e-9 * scale,
            "{} vs {xp}",
            last.position[0]
        );
        assert!((last.velocity[0] - vp).abs() < 1e-9 * scale * omega);
        assert_eq!(last.position[1], 0.0);

        // Amplitude and phase of the displacement u = x − l0 at 57.2 s:
        // u = A cos φ, v = −A ω sin φ, against A0 = 50, φ = ω t.
        let u = last.position[0] - osc.rest_length;
        let amp = u.hypot(last.velocity[0] / omega);
        let phase = (-last.velocity[0] / omega).atan2(u);
        let exact_phase = omega * last.t;
        let dphi = (phase - exact_phase + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        let det = 1.0 + (substeps as f64 - 1.0) / (2.0 * substeps as f64) * (omega * 0.2).powi(2);
        let growth = det.powf(steps as f64 / 2.0);
        let max_err = samples
            .iter()
            .map(|s| (s.position[0] - osc.position(s.t)).abs())
            .fold(0.0, f64::max);
        let energies: Vec<f64> = samples
            .iter()
            .map(|s| osc.energy_of(s.position[0], s.velocity[0]) / osc.energy() - 1.0)
            .collect();
        let (emin, emax) = energies
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &e| (a.min(e), b.max(e)));
        eprintln!(
            "rapier spring, dt 0.2, {substeps} substeps, t = 57.2 s: x = {:.6} m (exact {:.6}), \
             error {:.6} m, max |error| {max_err:.4} m, amplitude {amp:.4} m = {:.4} × A0 \
             (√det^n = {growth:.4}), phase error {dphi:.5} rad, ΔE/E0 in [{emin:.4}, {emax:.4}]",
            last.position[0],
            osc.position(last.t),
            last.position[0] - osc.position(last.t),
            amp / osc.amplitude(),
        );
        if substeps == 1 {
            // Semi-implicit Euler: docs/cases.md band [−0.1365, +0.1878].
            assert!((emin + 0.1365).abs() < 2e-3 && (emax - 0.1878).abs() < 2e-3);
            assert!((amp / osc.amplitude() - 1.0).abs() < 0.2);
        } else {
            // The non-normal map makes the measured amplitude oscillate
            // around √det^n by O(ωdt).
            assert!((amp / osc.amplitude() / growth - 1.0).abs() < 0.25, "{amp}");
        }
    }
}

/// Rapier's step map for a particle under gravity g and a force F(x, v)
/// evaluated at the start of each step and held: s substeps of
/// v += (F/m + g)·h, x += v·h.
fn held_force_particle(
    m: f64,
    g: [f64; 2],
    force: impl Fn([f64; 2], [f64; 2]) -> [f64; 2],
    x0: [f64; 2],
    v0: [f64; 2],
    settings: &RapierSettings,
    steps: usize,
) -> ([f64; 2], [f64; 2]) {
    let h = settings.dt / settings.substeps as f64;
    let (mut x, mut v) = (x0, v0);
    for _ in 0..steps {
        let f = force(x, v);
        for _ in 0..settings.substeps {
            for i in 0..2 {
                v[i] += (f[i] / m + g[i]) * h;
                x[i] += v[i] * h;
            }
        }
    }
    (x, v)
}

/// Quadratic-drag projectile (`docs/cases.md` `projectile_drag`) at dt = 0.01 s
/// against the DOP853 reference at t = 5 s. The drag is evaluated at the
/// start of each step and held (explicit Euler in the drag, O(dt)), on top
/// of the symplectic-Euler O(dt/s) of gravity: the error is first order,
/// halving dt halves it. Rapier's trace is also checked, to round-off,
/// against that held-force step map.
#[test]
fn rapier_drag_projectile_is_first_order() {
    let reference = DragReference::compute().unwrap();
    let want = reference.state_at(5.0).unwrap();
    let params = reference.params();
    let (s, c) = params.angle.sin_cos();
    let body = seed_box([params.speed * c, params.speed * s]);
    let forces = [
        RapierForce::Gravity([0.0, -params.gravity]),
        RapierForce::QuadraticDrag {
            coefficient: params.drag,
        },
    ];
    let mut errors = Vec::new();
    for dt in [0.01, 0.005] {
        let samples = run_single_body(&body, &forces, &RapierSettings::new(dt), 5.0).unwrap();
        let last = samples.last().unwrap();
        let (xp, vp) = held_force_particle(
            params.mass,
            [0.0, -params.gravity],
            |_, v| {
                let k = params.drag * v[0].hypot(v[1]);
                [-k * v[0], -k * v[1]]
            },
            body.position,
            body.velocity,
            &RapierSettings::new(dt),
            samples.len() - 1,
        );
        for i in 0..2 {
            assert!(
                (last.position[i] - xp[i]).abs() < 1e-9,
                "{:?} {xp:?}",
                last.position
            );
            assert!(
                (last.velocity[i] - vp[i]).abs() < 1e-9,
                "{:?} {vp:?}",
                last.velocity
            );
        }
        let e = [
            last.position[0] - want[0],
            last.position[1] - want[1],
            last.velocity[0] - want[2],
            last.velocity[1] - want[3],
        ];
        let pos = e[0].hypot(e[1]);
        eprintln!(
            "rapier drag projectile, dt {dt}, 4 substeps, t = 5 s: error x {:.4e} m, y {:.4e} m \
             (|Δp| {pos:.4e} m), vx {:.4e} m/s, vy {:.4e} m/s",
            e[0], e[1], e[2], e[3]
        );
        errors.push(pos);
    }
    let ratio = errors[0] / errors[1];
    eprintln!("rapier drag projectile: error ratio dt/(dt/2) = {ratio:.4} (first order: 2)");
    assert!(errors[0] < 0.5, "{}", errors[0]);
    assert!((ratio - 2.0).abs() < 0.1, "{ratio}");
}

/// Torque pulse (`docs/cases.md` `torque`): τ = 0.005 N·m on I = 5e-4 kg·m²
/// for 0.7 s = 70 steps of 0.01 s. ω(0.7) = Σ τ/I·h over 280 substeps =
/// 7 rad/s to round-off. The angle: each substep rotates by atan(ω·h)
/// (rapier's linearised rotation), with ω already updated (symplectic
/// Euler, +α·h·t1/2 = +0.00875 rad at the end of the pulse); at 7 rad/s
/// atan loses (ωh)³/3 per substep, −5.7e-3 rad over the 3200 substeps to
/// 8.7 s. θ(8.7) is checked against that sum to round-off.
#[test]
fn rapier_torque_pulse_rotation_is_linearised() {
    let pulse = TorquePulse::seed();
    let settings = RapierSettings::new(0.01);
    let body = RapierBody {
        inertia: Some(pulse.inertia),
        ..seed_box([0.0, 0.0])
    };
    let forces = [RapierForce::Torque {
        torque: pulse.torque,
        start: 0.0,
        end: pulse.duration,
    }];
    let samples = run_single_body(&body, &forces, &settings, 8.7).unwrap();
    assert_eq!(samples.len(), 871);
    let at_pulse_end = &samples[70];
    let last = samples.last().unwrap();

    // Prediction: rapier's substep map on ω and θ.
    let h = settings.dt / settings.substeps as f64;
    let dw = pulse.torque * (1.0 / pulse.inertia) * h;
    let (mut w, mut theta, mut theta_symplectic) = (0.0f64, 0.0f64, 0.0f64);
    for n in 0..870 {
        let on = step_in_window(n, settings.dt, 0.0, pulse.duration);
        for _ in 0..settings.substeps {
            if on {
                w += dw;
            }
            theta += (w * h).atan();
            theta_symplectic += w * h;
        }
    }
    eprintln!(
        "rapier torque pulse, dt 0.01, 4 substeps: ω(0.7) = {:.15} rad/s (exact 7), \
         θ(0.7) = {:.9} rad (exact 2.45), θ(8.7) = {:.9} rad (exact 58.45, error {:.4e}; \
         symplectic Euler alone {:.9}, predicted with atan {:.9})",
        at_pulse_end.angular_velocity,
        at_pulse_end.angle,
        last.angle,
        last.angle - pulse.theta(8.7),
        theta_symplectic,
        theta,
    );
    assert!((at_pulse_end.angular_velocity - pulse.omega(0.7)).abs() < 1e-12);
    assert!((last.angular_velocity - 7.0).abs() < 1e-12);
    assert!(
        (last.angle - theta).abs() < 1e-9,
        "{} vs {theta}",
        last.angle
    );
    assert!((theta_symplectic - 58.45875).abs() < 1e-9);
    // Just before and after the edge: step 69 is in, step 70 is out.
    assert!(step_in_window(69, 0.01, 0.0, 0.7) && !step_in_window(70, 0.01, 0.0, 0.7));
    assert!(last.position == [0.0, 0.0] && last.velocity == [0.0, 0.0]);
}

/// Angular drag with the 0.7 s torque (`docs/cases.md` `angular_drag`): the
/// stiff term of case II (D/I = 6 s⁻¹·(rad/s)⁻¹), run in rapier at dt =
/// 0.01 s and reported against the closed form.
#[test]
fn rapier_angular_drag_tracks_closed_form() {
    let exact = crate::AngularDrag::seed();
    let body = seed_box([0.0, 0.0]);
    let forces = [
        RapierForce::Torque {
            torque: 0.005,
            start: 0.0,
            end: 0.7,
        },
        RapierForce::AngularDrag { coefficient: 0.003 },
    ];
    let samples = run_single_body(&body, &forces, &RapierSettings::new(0.01), 8.7).unwrap();
    let (w07, w87) = (samples[70].angular_velocity, samples[870].angular_velocity);
    let (t07, t87) = (samples[70].angle, samples[870].angle);
    eprintln!(
        "rapier angular drag, dt 0.01: ω(0.7) = {w07:.9} (exact {:.9}), θ(0.7) = {t07:.9} \
         (exact {:.9}), ω(8.7) = {w87:.9} (exact {:.9}), θ(8.7) = {t87:.9} (exact {:.9})",
        exact.omega(0.7),
        exact.theta(0.7),
        exact.omega(8.7),
        exact.theta(8.7),
    );
    assert!((w07 - exact.omega(0.7)).abs() < 1e-2);
    assert!((t87 - exact.theta(8.7)).abs() < 5e-2);
}

/// Along the x axis with the body on the anchor's +x side, a distance
/// spring pulls exactly as the axial spring along x: ψ = |d| − l0 = d·u −
/// l0 and d/|d| = u. The two forces differ by the rounding of
/// k(|d| − l0)/|d|·d against k(d·u − l0)·u (an ulp or two per step), so
/// the runs agree to 1e-12 of the amplitude over 100 steps.
#[test]
fn a_distance_spring_along_x_pulls_as_the_axial_spring() {
    let osc = SpringOscillator::seed();
    let (body, axial) = spring_scene(&osc);
    let distance = [RapierForce::DistanceSpring {
        anchor: [0.0, 0.0],
        stiffness: osc.stiffness,
        rest_length: osc.rest_length,
    }];
    let settings = RapierSettings::new(0.01);
    let a = run_single_body(&body, &axial, &settings, 1.0).unwrap();
    let b = run_single_body(&body, &distance, &settings, 1.0).unwrap();
    assert_eq!(a.len(), 101);
    for (a, b) in a.iter().zip(&b) {
        assert!(a.position[0] > 0.0);
        assert!((a.position[0] - b.position[0]).abs() <= 1e-12 * osc.amplitude());
        assert!((a.velocity[0] - b.velocity[0]).abs() <= 1e-12 * osc.amplitude() * osc.omega());
        assert_eq!(b.position[1], 0.0);
    }
}
