//! Where tolerances come from. Each function states its derivation; a case
//! never types a bare number as a tolerance without one of these or a
//! written reason.

/// Relative round-off floor for quantities accumulated over up to ~10⁴
/// steps: each step adds a few ulps (2.2e-16), so 1e-9 relative is five
/// orders of magnitude above the accumulated round-off and far below any
/// discretization error the harness looks at.
pub const ROUND_OFF_RELATIVE: f64 = 1e-9;

/// Safety factor on the step-doubling (Richardson) estimate. In the
/// asymptotic range the estimate is exact to O(h); a factor 1.5 absorbs the
/// next-order term while a method whose real order is lower than claimed
/// (error halving instead of dividing by 2^p) would exceed it.
pub const RICHARDSON_FACTOR: f64 = 1.5;

/// Richardson estimate of the global error of an order-`p` method at step h,
/// from its results at h and h/2: `e(h) ≈ (y_h − y_{h/2}) / (1 − 2^−p)`.
pub fn richardson_error(value_h: f64, value_half: f64, order: u32) -> f64 {
    (value_h - value_half) / (1.0 - 0.5f64.powi(order as i32))
}

/// The tolerance for a fixed-step method's value against an exact
/// reference: [`RICHARDSON_FACTOR`] times the step-doubling estimate of its
/// own error, but never below the round-off floor `floor`.
pub fn from_order(value_h: f64, value_half: f64, order: u32, floor: f64) -> f64 {
    (RICHARDSON_FACTOR * richardson_error(value_h, value_half, order).abs()).max(floor)
}

/// The reason string that goes with [`from_order`].
pub fn from_order_reason(order: u32, floor: f64) -> String {
    format!(
        "{RICHARDSON_FACTOR} x step-doubling (Richardson) estimate of the order-{order} global error, floor {floor:e} (round-off)"
    )
}

/// Half a unit of the last digit of a value printed with `decimals`
/// decimals (the precision of a quoted reference number).
pub fn half_unit(decimals: i32) -> f64 {
    0.5 * 10f64.powi(-decimals)
}
