//! Scene files: a simulation's initial conditions in a text file instead of
//! Rust code, so that a user changes a scene without recompiling (the
//! seed's proposed extension, §8.3: « définir, avec n'importe quel éditeur
//! de texte, les conditions initiales des objets »).
//!
//! A scene is TOML. [`Scene::load`] reads, parses and validates it;
//! [`Scene::build_world`] turns it into an [`engine::World`]. Every mistake
//! (malformed TOML, an unknown key, NaN, mass ≤ 0, a clockwise polygon, a
//! force naming a missing body, ...) is a [`SceneError`] naming the file, the
//! field and the line, never a panic:
//!
//! ```text
//! scenes/spring.toml:19:8: bodies[0].mass: mass of body 'mass' must be > 0, got -20 kg
//! ```
//!
//! Limits, each refused with its reason and its line: a scene file is a
//! regular file of at most [`MAX_SCENE_BYTES`] (16 MiB) in UTF-8 (UTF-16 or
//! Latin-1 bytes are named as such); every number is 0 or between
//! [`MIN_MAGNITUDE`] (≈ 1.5e-154) and [`MAX_MAGNITUDE`] (≈ 1.3e154) in
//! magnitude, the square roots of f64's range, because the physics
//! multiplies quantities together; the mass and inertia derived from a
//! shape, the energy at t = 0 and a `[linear_test]`'s exact solution must
//! be finite; `dormand_prince`'s tolerance must exceed 10 ε ≈ 2.2e-15. A
//! world built from a scene reports a step whose energy stops being a
//! finite number as a blow-up ([`engine::EngineError::BlowUp`]).
//!
//! The format, field by field with units and defaults, is in [`mod@format`].
//! A complete example (every table; `#` starts a comment):
//!
//! ```
//! # use scene::Scene;
//! let text = r##"
//! [simulation]
//! method = "rk4"          # engine method id; default "rk4"
//! dt = 0.01               # s, > 0
//! duration = 8.7          # s, > 0; at most 1e8 steps
//! # tolerance = 1e-9      # dormand_prince only
//!
//! [[bodies]]
//! name = "box"
//! kind = "dynamic"        # or "static"; default "dynamic"
//! mass = 0.3              # kg (or density = ..., kg/m², with a shape)
//! # inertia = 5e-4        # kg·m²; default from the shape
//! shape = { type = "box", width = 0.1, height = 0.1 }   # m
//! position = [0.0, 0.0]   # m
//! angle = 0.0             # rad
//! velocity = [42.42640687119285, 42.42640687119285]     # m/s
//! angular_velocity = 0.0  # rad/s
//! colour = "#1f77b4"
//!
//! [[bodies]]
//! name = "wedge"
//! density = 2.0           # kg/m²: mass = 2 × area
//! shape = { type = "polygon", vertices = [[0, 0], [1, 0], [0, 1]] }  # CCW, simple
//! position = [5.0, 1.0]
//!
//! [[bodies]]
//! name = "bead"           # no shape, no inertia: a particle
//! mass = 1.0
//! position = [2.0, 0.0]
//!
//! [[bodies]]
//! name = "ground"
//! kind = "static"
//! shape = { type = "box", width = 1000.0, height = 1.0 }
//! position = [0.0, -0.5]
//!
//! [[forces]]
//! type = "gravity"
//! g = [0.0, -9.80655]     # m/s²
//!
//! [[forces]]
//! type = "drag"           # F = -D |v| v
//! body = "box"
//! coefficient = 0.003     # kg/m
//!
//! [[forces]]
//! type = "torque"         # tau = lever × force = 0.005 N·m
//! body = "box"
//! lever = [0.05, 0.05]    # m
//! force = [0.3, 0.4]      # N
//! window = [0.0, 0.7]     # s: on for 0 <= t < 0.7
//!
//! [[forces]]
//! type = "angular_drag"   # tau = -D w |w|
//! body = "box"
//! coefficient = 0.003     # N·m·s²
//!
//! [[forces]]
//! type = "spring"
//! body = "bead"
//! anchor = [0.0, 0.0]     # m (or other_body = "name")
//! stiffness = 50.0        # N/m
//! rest_length = 1.0       # m
//! axis = [1.0, 0.0]       # optional: a one-dimensional spring
//!
//! [[forces]]
//! type = "point_force"
//! body = "wedge"
//! force = [0.0, 1.0]      # N, world frame
//! point = [0.1, 0.0]      # m, body frame
//! window = [1.0, 2.0]
//!
//! [[events]]
//! type = "landing"        # y comes down through level; ends the run
//! body = "box"
//! level = 0.0             # m
//!
//! [[events]]
//! type = "apex"           # vy goes through 0 downwards
//! body = "box"
//!
//! [contact]               # turns contacts on (shapes collide)
//! model = "exact"         # few bodies, any method; default "soft_step"
//! restitution = 0.5
//! friction = 0.2
//! "##;
//! let scene = Scene::parse_str("example.toml", text)?;
//! assert_eq!(scene.body_names(), ["box", "wedge", "bead", "ground"]);
//! let mut world = scene.build_world(None)?;
//! let trace = world.run(scene.duration(), scene.dt())?;
//! assert!(trace.events.iter().any(|e| e.name == "apex"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The stiff test is a scene of its own, `[linear_test]` instead of bodies
//! (see [`LinearTest`]):
//!
//! ```
//! # use scene::Scene;
//! let scene = Scene::parse_str("hoffman.toml", r#"
//! [simulation]
//! method = "explicit_euler"
//! dt = 0.0019
//! duration = 1.0
//!
//! [linear_test]      # y' = lambda (y - (t + 2)) + 1
//! lambda = -1000.0
//! y0 = 1.0
//! "#)?;
//! let test = scene.linear_test().unwrap();
//! let solution = test.solve(scene.method(), scene.dt(), scene.duration())?;
//! let y = solution.y.last().unwrap()[0];
//! assert!((y - test.exact(1.0)).abs() < 1e-3);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

mod build;
mod chain;
mod colour;
mod energy_check;
pub mod error;
mod forces;
mod form_error;
pub mod format;
pub mod generate;
mod joint_grid;
mod joints;
mod linear_test;
mod load;
mod location;
pub mod outlines;
mod ragdoll;
mod read;

pub use build::{MAX_MAGNITUDE, MIN_MAGNITUDE};
pub use colour::Colour;
pub use error::{ErrorKind, SceneError};
pub use format::SceneFile;
pub use linear_test::LinearTest;
pub use load::Scene;
pub use read::MAX_SCENE_BYTES;
