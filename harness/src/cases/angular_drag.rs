//! Case II, `angular_drag` (CASES.md): the 0.7 s torque pulse against an
//! angular drag −D ω|ω|, D = 0.003; closed form tanh / ln cosh while driven,
//! hyperbolic decay after. The stiffest term of case II (I is tiny).

use super::CaseReport;
use super::torque::rotation_case;
use anyhow::Result;
use references::AngularDrag;

/// Runs the case.
pub fn run() -> Result<CaseReport> {
    let exact = AngularDrag::seed();
    rotation_case("angular_drag", true, |t| exact.omega(t), |t| exact.theta(t))
}
