//! The contact problem as a mixed linear complementarity problem, solved by
//! projected Gauss–Seidel and then polished to machine precision.
//!
//! Unknowns λ (impulses or forces, one per [`Row`]); residuals
//! `r = K λ + b`, with `b` the row's free motion minus its target:
//! - normal rows: `λ ≥ 0`, `r ≥ 0`, `λ r = 0` (push only, and only while
//!   the points would otherwise approach: Signorini);
//! - hold rows (a resting point left separating slowly, see the
//!   pipeline): λ of either sign, `r = 0`;
//! - friction rows: `|λ| ≤ μ max(0, Σ λ_normal)` of their manifold; `r = 0` inside
//!   the cone, `r ≥ 0` at its lower end and `r ≤ 0` at its upper end
//!   (Coulomb: sticking, or sliding with the largest friction).
//!
//! **Projected Gauss–Seidel** (the iteration of Box2D and rapier's
//! sequential impulses): sweep the rows, solve each for its own λ with the
//! others fixed, clamp to the bounds, until no λ moves. It converges
//! linearly. **Polish**: PGS tells which rows are active; with that active
//! set the problem is a small linear system, solved exactly by Gaussian
//! elimination; if that solution satisfies every condition it replaces the
//! PGS one. A box resting on two corners, sliding or held on an incline is
//! then exact to round-off (its acceleration is zero or the closed form's
//! to ~1e-16), which is what the harness's 1e-9 m checks need.

use super::rows::{Row, RowKind};

/// Read from `engine/src/tunables.rs` (unit, value and source there).
pub(crate) use crate::tunables::MAX_CONTACT_ROWS;

use crate::tunables::PGS_MAX_SWEEPS as MAX_SWEEPS;

use crate::tunables::PGS_TOLERANCE;

use crate::tunables::ACTIVE_THRESHOLD;

use crate::tunables::POLISH_TOLERANCE;

/// The bounds of row `k` given the current λ.
fn bounds(rows: &[Row], lambda: &[f64], k: usize) -> (f64, f64) {
    match rows[k].kind {
        RowKind::Normal => (0.0, f64::INFINITY),
        RowKind::Hold => (f64::NEG_INFINITY, f64::INFINITY),
        RowKind::Friction { mu, normals } => {
            // A held row may pull (λ < 0): the cone never turns inside out.
            let limit = mu * lambda[normals.0..normals.1].iter().sum::<f64>().max(0.0);
            (-limit, limit)
        }
    }
}

fn residual(k: &[f64], b: &[f64], lambda: &[f64], row: usize) -> f64 {
    let n = b.len();
    b[row]
        + k[row * n..(row + 1) * n]
            .iter()
            .zip(lambda)
            .map(|(kij, l)| kij * l)
            .sum::<f64>()
}

/// Solves the problem of `rows` with matrix `k` (row-major, n × n) and
/// free residuals `b` into `lambda`. Returns whether the polished (exact)
/// solution was taken.
pub(crate) fn solve(rows: &[Row], k: &[f64], b: &[f64], lambda: &mut Vec<f64>) -> bool {
    let n = rows.len();
    lambda.clear();
    lambda.resize(n, 0.0);
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if n == 0 || scale == 0.0 {
        return true;
    }
    for _ in 0..MAX_SWEEPS {
        let mut moved = 0.0f64;
        for row in 0..n {
            let kk = k[row * n + row];
            if kk <= 0.0 || !kk.is_finite() {
                continue;
            }
            let r = residual(k, b, lambda, row);
            let (lo, hi) = bounds(rows, lambda, row);
            let new = (lambda[row] - r / kk).clamp(lo, hi);
            moved = moved.max((new - lambda[row]).abs() * kk);
            lambda[row] = new;
        }
        if moved <= PGS_TOLERANCE * scale {
            break;
        }
    }
    match polish(rows, k, b, lambda, scale) {
        Some(exact) => {
            *lambda = exact;
            true
        }
        None => false,
    }
}

/// How a row enters the polished system.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Role {
    /// An unknown, with its column index.
    Unknown(usize),
    /// Zero (an inactive normal row, or friction with a zero bound).
    Zero,
    /// Friction at the bound `sign · μ Σ λ_normal`.
    Bound(f64),
}

fn polish(rows: &[Row], k: &[f64], b: &[f64], pgs: &[f64], scale: f64) -> Option<Vec<f64>> {
    let n = rows.len();
    let lambda_scale = pgs.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let tiny = ACTIVE_THRESHOLD * lambda_scale;
    let mut roles = vec![Role::Zero; n];
    let mut unknowns = Vec::with_capacity(n);
    for row in 0..n {
        roles[row] = match rows[row].kind {
            RowKind::Hold => {
                unknowns.push(row);
                Role::Unknown(unknowns.len() - 1)
            }
            RowKind::Normal => {
                if pgs[row] > tiny {
                    unknowns.push(row);
                    Role::Unknown(unknowns.len() - 1)
                } else {
                    Role::Zero
                }
            }
            RowKind::Friction { .. } => {
                let (_, hi) = bounds(rows, pgs, row);
                if hi <= tiny {
                    Role::Zero
                } else if pgs[row] >= hi - tiny {
                    Role::Bound(1.0)
                } else if pgs[row] <= -hi + tiny {
                    Role::Bound(-1.0)
                } else {
                    unknowns.push(row);
                    Role::Unknown(unknowns.len() - 1)
                }
            }
        };
    }
    let m = unknowns.len();
    // Column of each λ in terms of the unknowns: a bound friction row is
    // sign · μ · (sum of its normal unknowns).
    let column_of = |row: usize| -> Vec<(usize, f64)> {
        match roles[row] {
            Role::Unknown(c) => vec![(c, 1.0)],
            Role::Zero => Vec::new(),
            Role::Bound(sign) => match rows[row].kind {
                RowKind::Friction { mu, normals } => (normals.0..normals.1)
                    .filter_map(|p| match roles[p] {
                        Role::Unknown(c) => Some((c, sign * mu)),
                        _ => None,
                    })
                    .collect(),
                RowKind::Normal | RowKind::Hold => Vec::new(),
            },
        }
    };
    let columns: Vec<Vec<(usize, f64)>> = (0..n).map(column_of).collect();
    let mut a = vec![0.0; m * m];
    let mut rhs = vec![0.0; m];
    for (e, &row) in unknowns.iter().enumerate() {
        rhs[e] = -b[row];
        for (j, col) in columns.iter().enumerate() {
            for &(c, w) in col {
                a[e * m + c] += k[row * n + j] * w;
            }
        }
    }
    let x = gauss(&mut a, &mut rhs, m)?;
    let mut lambda = vec![0.0; n];
    for (j, col) in columns.iter().enumerate() {
        lambda[j] = col.iter().map(|&(c, w)| w * x[c]).sum();
    }
    // Verify every condition.
    let tol_l = POLISH_TOLERANCE * lambda_scale.max(f64::MIN_POSITIVE);
    let tol_r = POLISH_TOLERANCE * scale;
    for row in 0..n {
        let r = residual(k, b, &lambda, row);
        let ok = match (rows[row].kind, roles[row]) {
            (RowKind::Normal, Role::Unknown(_)) => lambda[row] >= -tol_l,
            (RowKind::Normal, _) => r >= -tol_r,
            (RowKind::Hold, _) => true,
            (RowKind::Friction { .. }, Role::Unknown(_)) => {
                let (_, hi) = bounds(rows, &lambda, row);
                lambda[row].abs() <= hi + tol_l
            }
            (RowKind::Friction { .. }, Role::Bound(sign)) => sign * r <= tol_r,
            (RowKind::Friction { .. }, Role::Zero) => true,
        };
        if !ok || !lambda[row].is_finite() {
            return None;
        }
    }
    for (row, l) in lambda.iter_mut().enumerate() {
        if rows[row].kind == RowKind::Normal {
            *l = l.max(0.0);
        }
    }
    Some(lambda)
}

/// Solves the m × m system `a x = rhs` (row-major `a`) by Gaussian
/// elimination with partial pivoting; `None` if it is singular to working
/// precision.
fn gauss(a: &mut [f64], rhs: &mut [f64], m: usize) -> Option<Vec<f64>> {
    let norm = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for col in 0..m {
        let pivot =
            (col..m).max_by(|&i, &j| a[i * m + col].abs().total_cmp(&a[j * m + col].abs()))?;
        let pivot_size = a[pivot * m + col].abs();
        if pivot_size.is_nan() || pivot_size <= 1e-13 * norm {
            return None;
        }
        if pivot != col {
            for c in 0..m {
                a.swap(pivot * m + c, col * m + c);
            }
            rhs.swap(pivot, col);
        }
        for r in col + 1..m {
            let f = a[r * m + col] / a[col * m + col];
            if f == 0.0 {
                continue;
            }
            for c in col..m {
                a[r * m + c] -= f * a[col * m + c];
            }
            rhs[r] -= f * rhs[col];
        }
    }
    let mut x = vec![0.0; m];
    for r in (0..m).rev() {
        let s: f64 = (r + 1..m).map(|c| a[r * m + c] * x[c]).sum();
        x[r] = (rhs[r] - s) / a[r * m + r];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::super::rows::{BodyView, Side, effective_mass};
    use super::*;
    use nalgebra::Vector2;

    fn ground_and_box(half: f64, m: f64) -> Vec<BodyView> {
        let i = m * (2.0 * half) * (2.0 * half) / 6.0;
        vec![
            BodyView {
                inv_mass: 0.0,
                inv_inertia: 0.0,
                position: Vector2::new(0.0, -0.5),
                velocity: Vector2::zeros(),
                omega: 0.0,
            },
            BodyView {
                inv_mass: 1.0 / m,
                inv_inertia: 1.0 / i,
                position: Vector2::new(0.0, half),
                velocity: Vector2::zeros(),
                omega: 0.0,
            },
        ]
    }

    fn rows_of_box(half: f64, mu: f64) -> Vec<Row> {
        let n = Vector2::y();
        let mut rows = Vec::new();
        for x in [-half, half] {
            let p = Vector2::new(x, 0.0);
            rows.push(Row {
                kind: RowKind::Normal,
                sides: [
                    Side {
                        body: 0,
                        sign: -1.0,
                        arm: p - Vector2::new(0.0, -0.5),
                    },
                    Side {
                        body: 1,
                        sign: 1.0,
                        arm: p - Vector2::new(0.0, half),
                    },
                ],
                measure: n,
                push: n,
                target: 0.0,
            });
        }
        if mu > 0.0 {
            let t = Vector2::new(-1.0, 0.0);
            rows.push(Row {
                kind: RowKind::Friction {
                    mu,
                    normals: (0, 2),
                },
                sides: [
                    Side {
                        body: 0,
                        sign: -1.0,
                        arm: Vector2::new(0.0, 0.5),
                    },
                    Side {
                        body: 1,
                        sign: 1.0,
                        arm: Vector2::new(0.0, -half),
                    },
                ],
                measure: t,
                push: t,
                target: 0.0,
            });
        }
        rows
    }

    #[test]
    fn box_resting_on_two_corners_carries_half_its_weight_on_each() {
        let (half, m, g) = (0.5, 2.0, 9.80665);
        let bodies = ground_and_box(half, m);
        let rows = rows_of_box(half, 0.0);
        let mut k = Vec::new();
        effective_mass(&rows, &bodies, &mut k);
        // Free relative normal acceleration: −g at both corners.
        let b = vec![-g, -g];
        let mut lambda = Vec::new();
        assert!(solve(&rows, &k, &b, &mut lambda));
        for l in &lambda {
            assert!((l - 0.5 * m * g).abs() < 1e-14, "{lambda:?}");
        }
    }

    #[test]
    fn friction_sticks_inside_the_cone_and_saturates_outside() {
        let (half, m) = (0.5, 1.0);
        let bodies = ground_and_box(half, m);
        let rows = rows_of_box(half, 0.5);
        let mut k = Vec::new();
        effective_mass(&rows, &bodies, &mut k);
        let mut lambda = Vec::new();
        // Pushed sideways by 3 N along +x (tangent t = −x): holds.
        let b = vec![-10.0, -10.0, 3.0];
        assert!(solve(&rows, &k, &b, &mut lambda));
        let r: Vec<f64> = (0..3).map(|i| residual(&k, &b, &lambda, i)).collect();
        assert!(r.iter().all(|v| v.abs() < 1e-12), "{r:?} {lambda:?}");
        // Pushed by 8 N > μ N = 5 N: slides with friction at the bound.
        let b = vec![-10.0, -10.0, 8.0];
        assert!(solve(&rows, &k, &b, &mut lambda));
        let normal = lambda[0] + lambda[1];
        assert!((lambda[2] + 0.5 * normal).abs() < 1e-12, "{lambda:?}");
        assert!(residual(&k, &b, &lambda, 2) > 0.0);
    }

    #[test]
    fn separating_rows_push_nothing() {
        let bodies = ground_and_box(0.5, 1.0);
        let rows = rows_of_box(0.5, 0.0);
        let mut k = Vec::new();
        effective_mass(&rows, &bodies, &mut k);
        let mut lambda = Vec::new();
        assert!(solve(&rows, &k, &[1.0, 2.0], &mut lambda));
        assert_eq!(lambda, vec![0.0, 0.0]);
    }
}
