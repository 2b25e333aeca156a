//! Case II (`projectile_drag`): the high-precision reference values of
//! `docs/cases.md`, as constants.
//!
//! The problem (seed §6.2, eq. 6.4–6.15, Table 6.2): a point of mass
//! m = 0.3 kg under gravity g = 9.80655 m/s² (the seed's value, not standard
//! gravity) and quadratic air drag F = −D|v|v with D = ρCA/2 = 0.003 kg/m,
//! launched from the origin at 60 m/s and 45°. It has no closed form in 2D.
//!
//! The values below are those `docs/cases.md` quotes, from a 40-digit
//! Taylor-series solve (mpmath), confirmed there by DOP853 and Radau at 1e-13.
//! They were re-checked while writing this crate with mpmath's Taylor-series
//! `odefun` at 30 digits and `findroot` for the events: every printed digit
//! agrees (e.g. landing 5.85465326333002230339730190877 s, apex time
//! 2.57051888771891801740060845841 s). [`crate::drag_projectile`] reproduces
//! them with DOP853 in `f64`; its tests state the agreement.
//!
//! Each value is printed to a fixed number of digits; half a unit of the last
//! printed digit is its rounding uncertainty, given in [`ALL`] as
//! [`ReferenceValue::half_unit`].

/// Landing time T (s): first t > 0 with y(t) = 0 (descending).
pub const LANDING_TIME: f64 = 5.854653263330;
/// Range R (m): x at the landing time.
pub const RANGE: f64 = 113.8638433141;
/// Apex height H (m): y where vy = 0.
pub const APEX_HEIGHT: f64 = 43.00523490712;
/// Apex time (s): t where vy = 0.
pub const APEX_TIME: f64 = 2.570518887719;
/// Apex abscissa (m): x where vy = 0.
pub const APEX_X: f64 = 68.34176280439;
/// Horizontal impact velocity vx at the landing time, m/s.
pub const IMPACT_VX: f64 = 9.559095582234;
/// Vertical impact velocity vy at the landing time, m/s.
pub const IMPACT_VY: f64 = -23.01932191094;

/// The time (s) at which the state below is given.
pub const STATE_TIME: f64 = 5.0;
/// x at [`STATE_TIME`] = 5 s, m.
pub const STATE_X: f64 = 104.7938286099;
/// y at [`STATE_TIME`] = 5 s, m.
pub const STATE_Y: f64 = 18.00633836691;
/// vx at [`STATE_TIME`] = 5 s, m/s.
pub const STATE_VX: f64 = 11.69691072171;
/// vy at [`STATE_TIME`] = 5 s, m/s.
pub const STATE_VY: f64 = -18.89837502420;

/// Euclidean position error |(Δx, Δy)| (m) at t = 5 s of classical RK4 with
/// h = 0.2 s (25 steps) against the reference state: `docs/cases.md` gives
/// 4.5e-4 m (2 significant digits; the unrounded value is 4.511e-4 m).
pub const RK4_H02_POSITION_ERROR_AT_5_S: f64 = 4.5e-4;

/// One printed reference value with its rounding uncertainty.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceValue {
    /// Short identifier, e.g. `"landing_time"`.
    pub name: &'static str,
    /// The value as printed in `docs/cases.md`.
    pub value: f64,
    /// SI unit of the value.
    pub unit: &'static str,
    /// Half a unit of the last printed digit: how far the printed value can
    /// be from the exact one by rounding alone.
    pub half_unit: f64,
}

/// Every high-precision value of `docs/cases.md` case II `projectile_drag` (not
/// the RK4 error, which is a property of a method, not of the solution).
pub const ALL: [ReferenceValue; 11] = [
    ReferenceValue {
        name: "landing_time",
        value: LANDING_TIME,
        unit: "s",
        half_unit: 5e-13,
    },
    ReferenceValue {
        name: "range",
        value: RANGE,
        unit: "m",
        half_unit: 5e-11,
    },
    ReferenceValue {
        name: "apex_height",
        value: APEX_HEIGHT,
        unit: "m",
        half_unit: 5e-12,
    },
    ReferenceValue {
        name: "apex_time",
        value: APEX_TIME,
        unit: "s",
        half_unit: 5e-13,
    },
    ReferenceValue {
        name: "apex_x",
        value: APEX_X,
        unit: "m",
        half_unit: 5e-12,
    },
    ReferenceValue {
        name: "impact_vx",
        value: IMPACT_VX,
        unit: "m/s",
        half_unit: 5e-13,
    },
    ReferenceValue {
        name: "impact_vy",
        value: IMPACT_VY,
        unit: "m/s",
        half_unit: 5e-12,
    },
    ReferenceValue {
        name: "state_at_5s_x",
        value: STATE_X,
        unit: "m",
        half_unit: 5e-11,
    },
    ReferenceValue {
        name: "state_at_5s_y",
        value: STATE_Y,
        unit: "m",
        half_unit: 5e-12,
    },
    ReferenceValue {
        name: "state_at_5s_vx",
        value: STATE_VX,
        unit: "m/s",
        half_unit: 5e-12,
    },
    ReferenceValue {
        name: "state_at_5s_vy",
        value: STATE_VY,
        unit: "m/s",
        half_unit: 5e-12,
    },
];
