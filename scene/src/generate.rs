//! `[[generate]]`: many bodies from a few numbers, so that a scene of
//! thousands of bodies is a short file a user can read.
//!
//! ```toml
//! [[generate]]
//! type = "pyramid"        # rows of boxes side by side, each row offset by half a box
//! base = 20               # boxes in the bottom row (210 in all)
//! box_size = 1.0          # m, the side of each box
//! spacing = 0.0           # m, the gap between neighbours in a row
//! origin = [0.0, 0.0]     # m, the middle of the bottom row's bottom edge
//! density = 1.0           # kg/m²
//!
//! [[generate]]
//! type = "stack"          # a vertical column of boxes
//! count = 15
//! box_size = 1.0
//! origin = [10.0, 0.0]    # m, the middle of the bottom box's bottom edge
//! jitter = 0.01           # m: each box moved sideways by a uniform random amount in ±jitter
//! seed = 7                # the random draws are the same on every machine
//!
//! [[generate]]
//! type = "grid"           # a rain of mixed shapes
//! rows = 10
//! columns = 100
//! origin = [-50.0, 20.0]  # m, the centre of the first (lower-left) body
//! spacing = [1.0, 1.0]    # m between centres
//! shapes = ["box", "circle", "polygon"]   # each body takes one at random
//! size = [0.3, 0.8]       # m, its size (side, diameter, span) drawn in this range
//! velocity = [0.0, -5.0]  # m/s
//! seed = 1
//! kind = "dynamic"        # or "static" (no velocity): Box2D's rain tiles are
//!                         # one row of static boxes, rows = 1, size = [0.5, 0.5]
//!
//! [[generate]]
//! type = "chain"          # box links on revolute joints (see chain.rs)
//! count = 20
//! link_length = 0.5       # m, pivot to pivot
//! link_width = 0.1        # m; default a quarter of link_length
//! start = [-4.0, 8.0]     # m, jointed to the world
//! end = [4.0, 8.0]        # m, jointed to the world; without it the chain
//!                         # is laid along `direction` (default [0, -1])
//!
//! [[generate]]
//! type = "ragdoll"        # Box2D's human: 11 bones, 10 revolute joints
//! position = [0.0, 2.0]   # m, the ground point under the hip
//! scale = 1.0             # 1: about 1.6 m tall
//! repeat = [5, 2]         # columns, rows of ragdolls; default [1, 1]
//! repeat_spacing = [1.0, 2.0]   # m between them
//! collision_groups = 5    # ragdolls share 5 groups; default one each
//! joint_friction = 0.05   # N·m at scale 1 (motors at speed 0); 0: none
//! joint_hertz = 5.0       # Hz of the joints' springs; 0: none
//! joint_damping_ratio = 0.5
//!
//! [[generate]]
//! type = "joint_grid"     # Box2D's joint_grid: circles on revolute joints
//! columns = 100           # along +x from origin
//! rows = 100              # along -y from origin
//! radius = 0.4            # m
//! spacing = 1.0           # m between neighbouring centres
//! origin = [0.0, 0.0]     # m, the top-left circle's centre
//! fixed = 7               # static circles in the middle of the top row
//! ```
//!
//! Every generator also takes `density` (kg/m², default 1), `friction` and
//! `restitution` (default: `[contact]`'s; a ragdoll's friction 0.2, Box2D's
//! human), `name` (the bodies are called
//! `name_0`, `name_1`, ... in the order built; default the generator's
//! type) and `colour` (one colour for the whole group; default the next in
//! the palette; a ragdoll's default is Box2D's trousers, shirt and skin).
//! The top box of a pyramid or stack is the last one built. A chain's
//! links are `name_0` … from `start`, its joints `name_j0` …; a ragdoll's
//! bones `name_hip`, `name_torso`, … (`name_3_hip` … for the fourth of a
//! grid). A joint grid's circles are `name_0` … column after column, top
//! to bottom (Box2D's order; see joint_grid.rs), its joints `name_j0` ….
//! Chains, ragdolls and joint grids have joints, so they need the
//! soft-step contact model (the default when the scene has no
//! `[contact]`). Static generated bodies (a static grid, a joint grid's
//! fixed circles) are grey unless the generator has a `colour`.
//!
//! Random draws come from SplitMix64 seeded by `seed`, written here rather
//! than taken from a crate so that a seed gives the same scene forever,
//! whatever crate versions a build resolves.

use crate::Colour;
use crate::build::{Checked, finite, non_negative, positive};
use crate::error::{ErrorKind, FieldPath, Problem};
use crate::format::Xy;
use engine::{BodyDef, BodyKind, BodyState, JointDef, Shape};
use nalgebra::Vector2;
use serde::Deserialize;

fn one() -> f64 {
    1.0
}

fn default_seed() -> i64 {
    1
}

fn yes() -> bool {
    true
}

/// Most bodies one scene may generate: beyond this a typo (a base of 1e6)
/// would exhaust memory rather than give an error.
pub const MAX_GENERATED: usize = 1_000_000;

/// A `[[generate]]` block.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum GenerateSpec {
    /// Rows of square boxes, `base` in the bottom row, one fewer in each
    /// row above, each row offset by half a box (Box2D's benchmark
    /// pyramid).
    Pyramid {
        /// Boxes in the bottom row, ≥ 1.
        base: i64,
        /// Side of each box (m), > 0. Default 1.
        #[serde(default = "one")]
        box_size: f64,
        /// Gap between neighbours in a row (m), ≥ 0. Default 0.
        #[serde(default)]
        spacing: f64,
        /// Fraction of a box by which each box overlaps its neighbours in
        /// its row and the rows above and below, in [0, 0.5): rows and
        /// boxes are `box_size · (1 − overlap)` apart (an overlap-recovery
        /// test). Default 0.
        #[serde(default)]
        overlap: f64,
        /// Middle of the bottom row's bottom edge (m). Default `[0, 0]`.
        #[serde(default)]
        origin: Xy,
        /// Copies of the pyramid along x and y, `[columns, rows]`, each an
        /// integer ≥ 1 (Box2D's "many pyramids"). Default `[1, 1]`.
        repeat: Option<Xy>,
        /// Offset between copies along x and y (m). Default `[0, 0]`
        /// (required when `repeat` asks for copies).
        #[serde(default)]
        repeat_spacing: Xy,
        /// Density (kg/m²), > 0. Default 1.
        #[serde(default = "one")]
        density: f64,
        /// Friction of each box. Default: `[contact] friction`.
        friction: Option<f64>,
        /// Restitution of each box. Default: `[contact] restitution`.
        restitution: Option<f64>,
        /// Name prefix. Default `"pyramid"`.
        name: Option<String>,
        /// Colour of the group, `"#rrggbb"`.
        colour: Option<String>,
    },
    /// A vertical column of square boxes, each shifted sideways by a random
    /// amount in ±`jitter`.
    Stack {
        /// Boxes, ≥ 1.
        count: i64,
        /// Side of each box (m), > 0. Default 1.
        #[serde(default = "one")]
        box_size: f64,
        /// Gap between boxes (m), ≥ 0. Default 0.
        #[serde(default)]
        spacing: f64,
        /// Middle of the bottom box's bottom edge (m). Default `[0, 0]`.
        #[serde(default)]
        origin: Xy,
        /// Largest sideways shift (m), ≥ 0. Default 0.
        #[serde(default)]
        jitter: f64,
        /// Seed of the random shifts. Default 1.
        #[serde(default = "default_seed")]
        seed: i64,
        /// Density (kg/m²), > 0. Default 1.
        #[serde(default = "one")]
        density: f64,
        /// Friction of each box. Default: `[contact] friction`.
        friction: Option<f64>,
        /// Restitution of each box. Default: `[contact] restitution`.
        restitution: Option<f64>,
        /// Name prefix. Default `"stack"`.
        name: Option<String>,
        /// Colour of the group, `"#rrggbb"`.
        colour: Option<String>,
    },
    /// `rows × columns` bodies on a regular grid, each a shape drawn at
    /// random from `shapes`, of a size drawn in `size`, turned by a random
    /// angle.
    Grid {
        /// Rows, ≥ 1.
        rows: i64,
        /// Columns, ≥ 1.
        columns: i64,
        /// Centre of the first (lower-left) body (m). Default `[0, 0]`.
        #[serde(default)]
        origin: Xy,
        /// Distance between centres along x and y (m), each > 0.
        spacing: Xy,
        /// Shapes to draw from: `"box"`, `"circle"`, `"polygon"` (a regular
        /// polygon of 3 to 8 sides), `"capsule"`, `"rounded_box"`,
        /// `"concave"` (an L piece). Default `["box"]`.
        #[serde(default = "default_shapes")]
        shapes: Vec<GridShape>,
        /// Size range `[min, max]` (m): a box's side, a circle's diameter,
        /// a polygon's circumscribed diameter, a capsule's overall length,
        /// a rounded box's outer side, an L piece's span; 0 < min ≤ max.
        /// Default `[1, 1]`.
        size: Option<Xy>,
        /// Initial velocity of every body (m/s). Default `[0, 0]`.
        #[serde(default)]
        velocity: Xy,
        /// Whether each body is turned by a random angle. Default true;
        /// false keeps every body upright (Box2D's tumbler).
        #[serde(default = "yes")]
        random_angle: bool,
        /// `"dynamic"` (the default) or `"static"`: fixed bodies without
        /// velocity or density, e.g. a row of tiles (Box2D's rain).
        #[serde(default)]
        kind: GridKind,
        /// Seed of the random draws. Default 1.
        #[serde(default = "default_seed")]
        seed: i64,
        /// Density (kg/m²), > 0. Default 1.
        #[serde(default = "one")]
        density: f64,
        /// Friction of each body. Default: `[contact] friction`.
        friction: Option<f64>,
        /// Restitution of each body. Default: `[contact] restitution`.
        restitution: Option<f64>,
        /// Name prefix. Default `"grid"`.
        name: Option<String>,
        /// Colour of the group, `"#rrggbb"`.
        colour: Option<String>,
    },
    /// `count` box links jointed end to end by revolute joints, hanging
    /// from the world at `start`, to the world at `end` too if given.
    Chain {
        /// Links, ≥ 1.
        count: i64,
        /// Length of a link pivot to pivot (m), > 0. Default 0.5.
        #[serde(default = "half")]
        link_length: f64,
        /// Width of a link (m), > 0. Default a quarter of `link_length`.
        link_width: Option<f64>,
        /// The first link's free end, jointed to the world (m). Required.
        start: Xy,
        /// The last link's free end, jointed to the world (m): the chain
        /// hangs between two anchors, and must reach. Default: none.
        end: Option<Xy>,
        /// Without `end`, the direction the links are laid along from
        /// `start` (non-zero). Default `[0, -1]` (hanging straight down).
        direction: Option<Xy>,
        /// Density (kg/m²), > 0. Default 1.
        #[serde(default = "one")]
        density: f64,
        /// Friction of each link. Default: `[contact] friction`.
        friction: Option<f64>,
        /// Restitution of each link. Default: `[contact] restitution`.
        restitution: Option<f64>,
        /// Name prefix. Default `"chain"`.
        name: Option<String>,
        /// Colour of the group, `"#rrggbb"`.
        colour: Option<String>,
    },
    /// Box2D's ragdoll (its `rain` benchmark's human): 11 bones on 10
    /// revolute joints with limits, joint friction (motors at speed 0) and
    /// springs; one ragdoll, or a grid of them.
    Ragdoll {
        /// The ground point under the first ragdoll's hip (m). Default
        /// `[0, 0]`.
        #[serde(default)]
        position: Xy,
        /// Size factor, > 0: 1 is Box2D's human, about 1.6 m tall.
        /// Default 1.
        #[serde(default = "one")]
        scale: f64,
        /// Copies along x and y, `[columns, rows]`, each a whole number
        /// ≥ 1. Default `[1, 1]`.
        repeat: Option<Xy>,
        /// Offset between copies along x and y (m). Default `[0, 0]`.
        #[serde(default)]
        repeat_spacing: Xy,
        /// How many collision groups the ragdolls share, a whole number
        /// ≥ 1: the ragdoll in column c and row r of `repeat` is in the
        /// ((c + 2r) mod n)-th, so that with 5 or more no two ragdolls
        /// side by side, one above the other or diagonal neighbours share
        /// one (Box2D's rain has 5; rapier takes at most 32 groups in a
        /// scene). Default: each ragdoll its own group.
        collision_groups: Option<i64>,
        /// Largest torque of each joint's friction motor at scale 1 (N·m),
        /// ≥ 0, times the bone's share (Box2D's) and the scale; 0: no
        /// motors. Default 0.05 (Box2D's rain).
        #[serde(default = "rain_friction")]
        joint_friction: f64,
        /// Frequency of each joint's spring (Hz), ≥ 0; 0: no springs.
        /// Default 5 (Box2D's rain).
        #[serde(default = "rain_hertz")]
        joint_hertz: f64,
        /// Damping ratio of the joints' springs, ≥ 0. Default 0.5.
        #[serde(default = "half")]
        joint_damping_ratio: f64,
        /// Initial velocity of every bone (m/s). Default `[0, 0]`.
        #[serde(default)]
        velocity: Xy,
        /// Density (kg/m²), > 0. Default 1.
        #[serde(default = "one")]
        density: f64,
        /// Friction of each bone. Default 0.2 (Box2D's human).
        friction: Option<f64>,
        /// Restitution of each bone. Default: `[contact] restitution`.
        restitution: Option<f64>,
        /// Name prefix. Default `"ragdoll"`.
        name: Option<String>,
        /// One colour for every bone, `"#rrggbb"`. Default Box2D's
        /// trousers, shirt and skin.
        colour: Option<String>,
    },
    /// Box2D's `joint_grid` benchmark: `columns` × `rows` circles, each
    /// joined to the one above it and the one on its left by a free
    /// revolute joint at the midpoint, hanging from static circles in the
    /// middle of the top row; the circles never collide with each other
    /// (see joint_grid.rs).
    JointGrid {
        /// Columns, ≥ 1, along +x.
        columns: i64,
        /// Rows, ≥ 1, along −y.
        rows: i64,
        /// Radius of each circle (m), > 0. Default 0.4 (Box2D's).
        #[serde(default = "grid_radius")]
        radius: f64,
        /// Distance between neighbouring centres (m), > 0. Default 1.
        #[serde(default = "one")]
        spacing: f64,
        /// Centre of the top-left circle (m). Default `[0, 0]`.
        #[serde(default)]
        origin: Xy,
        /// Static circles in the middle of the top row, from 0 to
        /// `columns`. Default 7 (Box2D's), or every column of a grid
        /// narrower than that.
        fixed: Option<i64>,
        /// Density (kg/m²), > 0. Default 1.
        #[serde(default = "one")]
        density: f64,
        /// Friction of each circle. Default: `[contact] friction`.
        friction: Option<f64>,
        /// Restitution of each circle. Default: `[contact] restitution`.
        restitution: Option<f64>,
        /// Name prefix. Default `"joint_grid"`.
        name: Option<String>,
        /// Colour of the moving circles, `"#rrggbb"` (the static ones
        /// are grey unless this is given).
        colour: Option<String>,
    },
}

fn grid_radius() -> f64 {
    0.4
}

/// Whether a `grid` generator's bodies move.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GridKind {
    /// Dynamic bodies (the default).
    #[default]
    Dynamic,
    /// Static bodies: no velocity, no density.
    Static,
}

fn half() -> f64 {
    0.5
}

fn rain_friction() -> f64 {
    0.05
}

fn rain_hertz() -> f64 {
    5.0
}

/// What a generator makes: bodies (in order), their colours when the
/// generator chooses them, and joints between them (by body id).
#[derive(Debug, Clone, Default)]
pub(crate) struct Generated {
    pub(crate) bodies: Vec<BodyDef>,
    pub(crate) colours: Option<Vec<Colour>>,
    pub(crate) joints: Vec<JointDef>,
}

/// A shape a `grid` generator can draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GridShape {
    /// A square box.
    Box,
    /// A circle.
    Circle,
    /// A regular polygon of 3 to 8 sides.
    Polygon,
    /// A capsule `size` long overall, its cap centres `size`/2 apart, of
    /// radius `size`/4.
    Capsule,
    /// A square box of outer side `size`: a core of side 0.8 `size`
    /// rounded by 0.1 `size`.
    RoundedBox,
    /// A concave L piece spanning `size` on each side, its arms `size`/2
    /// wide (decomposed into convex parts).
    Concave,
}

fn default_shapes() -> Vec<GridShape> {
    vec![GridShape::Box]
}

impl GenerateSpec {
    /// The generator's type, its default name prefix.
    pub fn kind(&self) -> &'static str {
        match self {
            GenerateSpec::Pyramid { .. } => "pyramid",
            GenerateSpec::Stack { .. } => "stack",
            GenerateSpec::Grid { .. } => "grid",
            GenerateSpec::Chain { .. } => "chain",
            GenerateSpec::Ragdoll { .. } => "ragdoll",
            GenerateSpec::JointGrid { .. } => "joint_grid",
        }
    }

    /// The name prefix of the generated bodies.
    pub fn prefix(&self) -> &str {
        let name = match self {
            GenerateSpec::Pyramid { name, .. }
            | GenerateSpec::Stack { name, .. }
            | GenerateSpec::Grid { name, .. }
            | GenerateSpec::Chain { name, .. }
            | GenerateSpec::Ragdoll { name, .. }
            | GenerateSpec::JointGrid { name, .. } => name,
        };
        name.as_deref().unwrap_or(self.kind())
    }

    /// The group's colour as written, if any.
    pub fn colour(&self) -> Option<&str> {
        match self {
            GenerateSpec::Pyramid { colour, .. }
            | GenerateSpec::Stack { colour, .. }
            | GenerateSpec::Grid { colour, .. }
            | GenerateSpec::Chain { colour, .. }
            | GenerateSpec::Ragdoll { colour, .. }
            | GenerateSpec::JointGrid { colour, .. } => colour.as_deref(),
        }
    }

    fn material(&self) -> (f64, Option<f64>, Option<f64>) {
        match self {
            GenerateSpec::Pyramid {
                density,
                friction,
                restitution,
                ..
            }
            | GenerateSpec::Stack {
                density,
                friction,
                restitution,
                ..
            }
            | GenerateSpec::Grid {
                density,
                friction,
                restitution,
                ..
            }
            | GenerateSpec::Chain {
                density,
                friction,
                restitution,
                ..
            }
            | GenerateSpec::JointGrid {
                density,
                friction,
                restitution,
                ..
            } => (*density, *friction, *restitution),
            GenerateSpec::Ragdoll {
                density,
                friction,
                restitution,
                ..
            } => (*density, Some(friction.unwrap_or(0.2)), *restitution),
        }
    }

    /// Whether the generator makes joints (so needs the soft step).
    pub fn has_joints(&self) -> bool {
        matches!(
            self,
            GenerateSpec::Chain { .. }
                | GenerateSpec::Ragdoll { .. }
                | GenerateSpec::JointGrid { .. }
        )
    }
}

/// SplitMix64 (Steele, Lea and Flood, 2014): 64 random bits per call.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi].
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

fn count(path: &FieldPath, value: i64, what: &str) -> Checked<usize> {
    if value < 1 || value as u64 > MAX_GENERATED as u64 {
        return Err(Problem::new(
            path,
            ErrorKind::InvalidValue,
            format!("{what} must be between 1 and {MAX_GENERATED}, got {value}"),
        ));
    }
    Ok(value as usize)
}

/// The bodies of generator `spec` at `path` (`generate[i]`), before
/// materials and colours are applied; their count is checked against what
/// the scene already holds (`so_far`).
pub(crate) fn expand(path: &FieldPath, spec: &GenerateSpec, so_far: usize) -> Checked<Generated> {
    let (density, friction, restitution) = spec.material();
    let density = positive(&path.key("density"), density, "density", "kg/m²")?;
    let friction = friction
        .map(|f| non_negative(&path.key("friction"), f, "friction", ""))
        .transpose()?;
    let restitution = restitution
        .map(|e| crate::build::unit_interval(&path.key("restitution"), e, "restitution"))
        .transpose()?;
    let prefix = spec.prefix();
    if prefix.trim().is_empty() {
        return Err(Problem::new(
            &path.key("name"),
            ErrorKind::InvalidValue,
            "a generator's name must not be empty",
        ));
    }
    let with_joints = match spec {
        GenerateSpec::Chain { .. } => Some(chain(path, spec, (so_far, density))?),
        GenerateSpec::Ragdoll { .. } => Some(ragdolls(path, spec, (so_far, density))?),
        GenerateSpec::JointGrid { .. } => Some(joint_grid(path, spec, (so_far, density))?),
        _ => None,
    };
    if let Some(mut out) = with_joints {
        for b in &mut out.bodies {
            b.friction = friction;
            b.restitution = restitution;
        }
        let field = match spec {
            GenerateSpec::Chain { .. } => "start",
            GenerateSpec::JointGrid { .. } => "origin",
            _ => "position",
        };
        checked(path, field, &out.bodies)?;
        return Ok(out);
    }
    let placed = match spec {
        GenerateSpec::Pyramid {
            base,
            box_size,
            spacing,
            overlap,
            origin,
            repeat,
            repeat_spacing,
            ..
        } => {
            let base = count(&path.key("base"), *base, "base")?;
            let (copies_x, copies_y) = copies(&path.key("repeat"), repeat.as_ref())?;
            let shift = crate::build::xy(&path.key("repeat_spacing"), repeat_spacing)?;
            let copies = copies_x.saturating_mul(copies_y);
            let total = (base * (base + 1) / 2).saturating_mul(copies);
            check_total(path, so_far, total)?;
            let size = positive(&path.key("box_size"), *box_size, "box_size", "m")?;
            let gap = non_negative(&path.key("spacing"), *spacing, "spacing", "m")?;
            let overlap = non_negative(&path.key("overlap"), *overlap, "overlap", "")?;
            if overlap >= 0.5 {
                return Err(Problem::new(
                    &path.key("overlap"),
                    ErrorKind::InvalidValue,
                    format!(
                        "overlap must be below 0.5 (half a box), got {}",
                        engine::error::readable(overlap)
                    ),
                ));
            }
            let origin = crate::build::xy(&path.key("origin"), origin)?;
            let square = Shape::rectangle(size, size).map_err(|e| Problem::engine(path, e))?;
            let pitch = size * (1.0 - overlap) + gap;
            let rise = size * (1.0 - overlap);
            let mut out = Vec::with_capacity(total);
            for cy in 0..copies_y {
                for cx in 0..copies_x {
                    let at = origin + Vector2::new(cx as f64 * shift.x, cy as f64 * shift.y);
                    for row in 0..base {
                        let n = base - row;
                        for column in 0..n {
                            let x = (column as f64 - 0.5 * (n as f64 - 1.0)) * pitch;
                            let y = 0.5 * size + row as f64 * rise;
                            out.push((square.clone(), at + Vector2::new(x, y), 0.0));
                        }
                    }
                }
            }
            out
        }
        GenerateSpec::Stack {
            count: n,
            box_size,
            spacing,
            origin,
            jitter,
            seed,
            ..
        } => {
            let n = count(&path.key("count"), *n, "count")?;
            check_total(path, so_far, n)?;
            let size = positive(&path.key("box_size"), *box_size, "box_size", "m")?;
            let gap = non_negative(&path.key("spacing"), *spacing, "spacing", "m")?;
            let jitter = non_negative(&path.key("jitter"), *jitter, "jitter", "m")?;
            let origin = crate::build::xy(&path.key("origin"), origin)?;
            let square = Shape::rectangle(size, size).map_err(|e| Problem::engine(path, e))?;
            let mut rng = SplitMix64(*seed as u64);
            (0..n)
                .map(|i| {
                    let dx = if jitter > 0.0 {
                        rng.range(-jitter, jitter)
                    } else {
                        0.0
                    };
                    let y = (i as f64 + 0.5) * size + i as f64 * gap;
                    (square.clone(), origin + Vector2::new(dx, y), 0.0)
                })
                .collect()
        }
        GenerateSpec::Grid {
            rows,
            columns,
            origin,
            spacing,
            shapes,
            size,
            seed,
            random_angle,
            ..
        } => {
            let rows = count(&path.key("rows"), *rows, "rows")?;
            let columns = count(&path.key("columns"), *columns, "columns")?;
            let total = rows.saturating_mul(columns);
            check_total(path, so_far, total)?;
            let origin = crate::build::xy(&path.key("origin"), origin)?;
            let sp = path.key("spacing");
            let dx = positive(&sp.index(0), spacing.x, "spacing along x", "m")?;
            let dy = positive(&sp.index(1), spacing.y, "spacing along y", "m")?;
            if shapes.is_empty() {
                return Err(Problem::new(
                    &path.key("shapes"),
                    ErrorKind::InvalidValue,
                    "name at least one shape: \"box\", \"circle\" or \"polygon\"",
                ));
            }
            let size = size.unwrap_or(Xy { x: 1.0, y: 1.0 });
            let zp = path.key("size");
            let lo = positive(&zp.index(0), size.x, "smallest size", "m")?;
            let hi = positive(&zp.index(1), size.y, "largest size", "m")?;
            if hi < lo {
                return Err(Problem::new(
                    &zp,
                    ErrorKind::InvalidValue,
                    format!(
                        "size [{}, {}] m must be [smallest, largest]",
                        engine::error::readable(lo),
                        engine::error::readable(hi)
                    ),
                ));
            }
            let mut rng = SplitMix64(*seed as u64);
            let mut out = Vec::with_capacity(total);
            for row in 0..rows {
                for column in 0..columns {
                    let kind = shapes[(rng.next() % shapes.len() as u64) as usize];
                    let d = rng.range(lo, hi);
                    let angle = rng.range(-std::f64::consts::PI, std::f64::consts::PI);
                    let angle = if *random_angle { angle } else { 0.0 };
                    let shape =
                        grid_shape(kind, d, &mut rng).map_err(|e| Problem::engine(path, e))?;
                    let at = origin + Vector2::new(column as f64 * dx, row as f64 * dy);
                    out.push((shape, at, angle));
                }
            }
            out
        }
        GenerateSpec::Chain { .. }
        | GenerateSpec::Ragdoll { .. }
        | GenerateSpec::JointGrid { .. } => {
            unreachable!("generators with joints returned above")
        }
    };
    let velocity = match spec {
        GenerateSpec::Grid { velocity, .. } => crate::build::xy(&path.key("velocity"), velocity)?,
        _ => Vector2::zeros(),
    };
    let fixed = matches!(
        spec,
        GenerateSpec::Grid {
            kind: GridKind::Static,
            ..
        }
    );
    if fixed && velocity != Vector2::zeros() {
        return Err(Problem::new(
            &path.key("velocity"),
            ErrorKind::InvalidValue,
            "a static grid's bodies never move: remove `velocity`, or make the grid dynamic",
        ));
    }
    let bodies = placed
        .into_iter()
        .enumerate()
        .map(|(k, (shape, position, angle))| BodyDef {
            friction,
            restitution,
            ..generated_body(
                format!("{prefix}_{k}"),
                shape,
                (density, fixed),
                BodyState {
                    position,
                    angle,
                    velocity,
                    angular_velocity: 0.0,
                },
            )
        })
        .collect::<Vec<_>>();
    checked(path, "origin", &bodies)?;
    Ok(Generated {
        bodies,
        colours: None,
        joints: Vec::new(),
    })
}

/// `repeat = [columns, rows]`: whole numbers from 1; `[1, 1]` when absent.
fn copies(path: &FieldPath, repeat: Option<&Xy>) -> Checked<(usize, usize)> {
    let Some(r) = repeat else {
        return Ok((1, 1));
    };
    let whole = |i: usize, v: f64| -> Checked<usize> {
        if v.fract() != 0.0 || !(1.0..=MAX_GENERATED as f64).contains(&v) {
            return Err(Problem::new(
                &path.index(i),
                ErrorKind::InvalidValue,
                format!(
                    "a number of copies must be a whole number from 1 to {MAX_GENERATED}, got {}",
                    engine::error::readable(v)
                ),
            ));
        }
        Ok(v as usize)
    };
    Ok((whole(0, r.x)?, whole(1, r.y)?))
}

/// The engine's check of generated bodies, and of their positions'
/// finiteness (huge origins), at the generator's `field`.
fn checked(path: &FieldPath, field: &str, bodies: &[BodyDef]) -> Checked<()> {
    for def in bodies {
        engine::Body::from_def(def).map_err(|e| Problem::engine(path, e))?;
    }
    if let Some(last) = bodies.last() {
        finite(
            &path.key(field),
            last.state.position.x + last.state.position.y,
        )?;
    }
    Ok(())
}

/// A chain's links and joints.
fn chain(
    path: &FieldPath,
    spec: &GenerateSpec,
    (so_far, density): (usize, f64),
) -> Checked<Generated> {
    let GenerateSpec::Chain {
        count: n,
        link_length,
        link_width,
        start,
        end,
        direction,
        ..
    } = spec
    else {
        unreachable!("called for chains");
    };
    let n = count(&path.key("count"), *n, "count")?;
    check_total(path, so_far, n)?;
    let chain = crate::chain::ChainSpec {
        count: n,
        link_length: *link_length,
        link_width: *link_width,
        start,
        end: end.as_ref(),
        direction: direction.as_ref(),
    };
    let (bodies, joints) = crate::chain::expand(path, &chain, (spec.prefix(), so_far), density)?;
    Ok(Generated {
        bodies,
        colours: None,
        joints,
    })
}

/// A joint grid's circles and joints.
fn joint_grid(
    path: &FieldPath,
    spec: &GenerateSpec,
    (so_far, density): (usize, f64),
) -> Checked<Generated> {
    let GenerateSpec::JointGrid {
        columns,
        rows,
        radius,
        spacing,
        origin,
        fixed,
        ..
    } = spec
    else {
        unreachable!("called for joint grids");
    };
    let columns = count(&path.key("columns"), *columns, "columns")?;
    let rows = count(&path.key("rows"), *rows, "rows")?;
    check_total(path, so_far, columns.saturating_mul(rows))?;
    let grid = crate::joint_grid::JointGridSpec {
        columns,
        rows,
        radius: *radius,
        spacing: *spacing,
        origin,
        fixed: *fixed,
    };
    let (bodies, joints) =
        crate::joint_grid::expand(path, &grid, (spec.prefix(), so_far), density)?;
    Ok(Generated {
        bodies,
        colours: None,
        joints,
    })
}

/// Ragdolls' bones and joints, each ragdoll its own collision group (the
/// id of its first bone), or, with `collision_groups = n`, the ragdoll in
/// column c and row r in the group numbered by the id of the generator's
/// ((c + 2r) mod n)-th body (ids of this generator's bodies: no other
/// generator numbers a group the same).
fn ragdolls(
    path: &FieldPath,
    spec: &GenerateSpec,
    (so_far, density): (usize, f64),
) -> Checked<Generated> {
    let GenerateSpec::Ragdoll {
        position,
        scale,
        repeat,
        repeat_spacing,
        joint_friction,
        joint_hertz,
        joint_damping_ratio,
        velocity,
        collision_groups,
        ..
    } = spec
    else {
        unreachable!("called for ragdolls");
    };
    let (columns, rows) = copies(&path.key("repeat"), repeat.as_ref())?;
    let total = columns.saturating_mul(rows);
    check_total(path, so_far, total.saturating_mul(crate::ragdoll::BONES))?;
    let shared = collision_groups
        .map(|n| count(&path.key("collision_groups"), n, "collision_groups"))
        .transpose()?;
    if let Some(n) = shared.filter(|&n| n > total) {
        return Err(Problem::new(
            &path.key("collision_groups"),
            ErrorKind::InvalidValue,
            format!("{n} collision groups for {total} ragdolls: give at most one per ragdoll"),
        ));
    }
    let origin = crate::build::xy(&path.key("position"), position)?;
    let shift = crate::build::xy(&path.key("repeat_spacing"), repeat_spacing)?;
    let doll = crate::ragdoll::RagdollSpec {
        scale: *scale,
        joint_friction: *joint_friction,
        joint_hertz: *joint_hertz,
        joint_damping_ratio: *joint_damping_ratio,
        density,
        velocity: crate::build::xy(&path.key("velocity"), velocity)?,
    };
    let mut out = Generated {
        colours: Some(Vec::new()),
        ..Generated::default()
    };
    for row in 0..rows {
        for column in 0..columns {
            let k = row * columns + column;
            let name = if total == 1 {
                spec.prefix().to_owned()
            } else {
                format!("{}_{k}", spec.prefix())
            };
            let first = so_far + out.bodies.len();
            let group = match shared {
                None => first,
                Some(n) => so_far + (column + 2 * row) % n,
            };
            let group = u32::try_from(group).unwrap_or(u32::MAX);
            let at = origin + Vector2::new(column as f64 * shift.x, row as f64 * shift.y);
            let (bodies, colours, joints) =
                crate::ragdoll::expand(path, &doll, at, (&name, first, group))?;
            out.bodies.extend(bodies);
            if let Some(c) = out.colours.as_mut() {
                c.extend(colours);
            }
            out.joints.extend(joints);
        }
    }
    if spec.colour().is_some() {
        out.colours = None;
    }
    Ok(out)
}

fn check_total(path: &FieldPath, so_far: usize, more: usize) -> Checked<()> {
    if so_far.saturating_add(more) > MAX_GENERATED {
        return Err(Problem::new(
            path,
            ErrorKind::InvalidValue,
            format!(
                "this generator makes {more} bodies and the scene already has {so_far}: at most {MAX_GENERATED} in all"
            ),
        ));
    }
    Ok(())
}

/// A shape of kind `kind` and size `d` (m).
fn grid_shape(kind: GridShape, d: f64, rng: &mut SplitMix64) -> engine::Result<Shape> {
    match kind {
        GridShape::Box => Shape::rectangle(d, d),
        GridShape::Circle => Shape::circle(0.5 * d),
        GridShape::Capsule => Shape::capsule(0.5 * d, 0.25 * d),
        GridShape::RoundedBox => Shape::rounded_box(0.8 * d, 0.8 * d, 0.1 * d),
        GridShape::Concave => {
            // The L's outline counter-clockwise, its bounding square
            // centred on the origin.
            let h = 0.5 * d;
            let outline = [(-h, -h), (h, -h), (h, 0.0), (0.0, 0.0), (0.0, h), (-h, h)]
                .map(|(x, y)| Vector2::new(x, y));
            Ok(Shape::simple_polygon(&outline)?.centered())
        }
        GridShape::Polygon => {
            let sides = 3 + (rng.next() % 6) as usize;
            let r = 0.5 * d;
            let vertices = (0..sides)
                .map(|i| {
                    let a = 2.0 * std::f64::consts::PI * i as f64 / sides as f64;
                    Vector2::new(r * a.cos(), r * a.sin())
                })
                .collect();
            Shape::polygon(vertices)
        }
    }
}

/// A generated body: `shape` at `state`, of density `density.0` (kg/m²),
/// or static (no density) when `density.1`; materials from `[contact]`, no
/// collision group (the generators that need one add it with
/// `BodyDef::with_collision_group`).
pub(crate) fn generated_body(
    name: String,
    shape: Shape,
    (density, fixed): (f64, bool),
    state: BodyState,
) -> BodyDef {
    BodyDef {
        name,
        kind: if fixed {
            BodyKind::Static
        } else {
            BodyKind::Dynamic
        },
        mass: None,
        density: (!fixed).then_some(density),
        inertia: None,
        shape: Some(shape),
        state,
        friction: None,
        restitution: None,
        filter: engine::Filter::DEFAULT,
        sensor: false,
        rolling_resistance: None,
        tangent_speed: None,
        bullet: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pyramid(base: i64) -> GenerateSpec {
        GenerateSpec::Pyramid {
            base,
            box_size: 1.0,
            spacing: 0.0,
            overlap: 0.0,
            origin: Xy { x: 0.0, y: 0.0 },
            repeat: None,
            repeat_spacing: Xy::default(),
            density: 1.0,
            friction: None,
            restitution: None,
            name: None,
            colour: None,
        }
    }

    #[test]
    fn a_pyramid_has_its_triangle_number_of_boxes_touching_side_by_side() {
        let bodies = expand(&FieldPath::root().key("generate").index(0), &pyramid(4), 0)
            .unwrap()
            .bodies;
        assert_eq!(bodies.len(), 10);
        let xs: Vec<f64> = bodies[..4].iter().map(|b| b.state.position.x).collect();
        assert_eq!(xs, [-1.5, -0.5, 0.5, 1.5]);
        let top = bodies.last().unwrap();
        assert_eq!((top.state.position.x, top.state.position.y), (0.0, 3.5));
        assert_eq!(top.name, "pyramid_9");
    }

    #[test]
    fn the_same_seed_gives_the_same_grid() {
        let grid = |seed| GenerateSpec::Grid {
            rows: 3,
            columns: 4,
            origin: Xy::default(),
            spacing: Xy { x: 1.0, y: 1.0 },
            shapes: vec![GridShape::Box, GridShape::Circle, GridShape::Polygon],
            size: Some(Xy { x: 0.3, y: 0.8 }),
            velocity: Xy::default(),
            random_angle: true,
            kind: GridKind::Dynamic,
            seed,
            density: 1.0,
            friction: None,
            restitution: None,
            name: None,
            colour: None,
        };
        let path = FieldPath::root().key("generate").index(0);
        let a = expand(&path, &grid(5), 0).unwrap().bodies;
        assert_eq!(a, expand(&path, &grid(5), 0).unwrap().bodies);
        assert_ne!(a, expand(&path, &grid(6), 0).unwrap().bodies);
        assert_eq!(a.len(), 12);
    }

    #[test]
    fn out_of_range_counts_are_refused_at_their_field() {
        let path = FieldPath::root().key("generate").index(2);
        let err = expand(&path, &pyramid(0), 0).unwrap_err();
        assert_eq!(err.path.to_string(), "generate[2].base");
        let err = expand(&path, &pyramid(2000), 0).unwrap_err();
        assert!(err.message.contains("at most"), "{}", err.message);
    }
}
