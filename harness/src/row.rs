//! One validation row: a measured value, what it is compared with, the
//! tolerance and why, and the verdict. Rows are what `reports/summary.json`
//! holds and what the harness's exit code is judged on.

use serde::Serialize;

/// How `value` is judged against `expected`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Comparison {
    /// `|value − expected| ≤ tolerance`.
    Within,
    /// `value ≥ expected − tolerance` (e.g. a blow-up past a threshold).
    AtLeast,
    /// `value ≤ expected + tolerance` (e.g. an upper energy band).
    AtMost,
}

/// A validation row of `reports/summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Case id (`spring`, `projectile`, ...).
    pub case: String,
    /// What is checked (`x_end`, `landing_time`, ...).
    pub check: String,
    /// Method id.
    pub method: String,
    /// What else tells this row from a row of the same case, check, method
    /// and step (e.g. the stability axis); empty when nothing does.
    pub variant: String,
    /// Step (s); for Dormand–Prince the output interval.
    pub dt: f64,
    /// What the engine produced.
    pub value: f64,
    /// What it is compared with.
    pub expected: f64,
    /// Allowed difference, in the unit of the value.
    pub tolerance: f64,
    /// The verdict.
    pub pass: bool,
    /// How the comparison is made.
    pub comparison: Comparison,
    /// Where `expected` and `tolerance` come from.
    pub reason: String,
}

impl Row {
    /// A row judged by `comparison`; the verdict is computed here. A NaN
    /// value never passes.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        case: &str,
        check: &str,
        method: &str,
        dt: f64,
        value: f64,
        expected: f64,
        tolerance: f64,
        comparison: Comparison,
        reason: impl Into<String>,
    ) -> Self {
        let pass = match comparison {
            Comparison::Within => (value - expected).abs() <= tolerance,
            Comparison::AtLeast => value >= expected - tolerance,
            Comparison::AtMost => value <= expected + tolerance,
        };
        Self {
            case: case.into(),
            check: check.into(),
            method: method.into(),
            variant: String::new(),
            dt,
            value,
            expected,
            tolerance,
            pass,
            comparison,
            reason: reason.into(),
        }
    }
}

impl Row {
    /// The same row told apart from its neighbours by `variant`.
    pub fn with_variant(mut self, variant: impl Into<String>) -> Self {
        self.variant = variant.into();
        self
    }
}

/// Collects rows for one case and method at one step.
#[derive(Debug)]
pub struct RowSink<'a> {
    /// Case id.
    pub case: &'a str,
    /// Method id.
    pub method: &'a str,
    /// Step (s).
    pub dt: f64,
    /// Rows so far.
    pub rows: &'a mut Vec<Row>,
}

impl RowSink<'_> {
    /// Adds `|value − expected| ≤ tolerance`.
    pub fn within(
        &mut self,
        check: &str,
        value: f64,
        expected: f64,
        tolerance: f64,
        reason: impl Into<String>,
    ) {
        self.push(
            check,
            value,
            expected,
            tolerance,
            Comparison::Within,
            reason,
        );
    }

    /// Adds `value ≥ expected − tolerance`.
    pub fn at_least(
        &mut self,
        check: &str,
        value: f64,
        expected: f64,
        tolerance: f64,
        reason: impl Into<String>,
    ) {
        self.push(
            check,
            value,
            expected,
            tolerance,
            Comparison::AtLeast,
            reason,
        );
    }

    /// Adds `value ≤ expected + tolerance`.
    pub fn at_most(
        &mut self,
        check: &str,
        value: f64,
        expected: f64,
        tolerance: f64,
        reason: impl Into<String>,
    ) {
        self.push(
            check,
            value,
            expected,
            tolerance,
            Comparison::AtMost,
            reason,
        );
    }

    fn push(
        &mut self,
        check: &str,
        value: f64,
        expected: f64,
        tolerance: f64,
        comparison: Comparison,
        reason: impl Into<String>,
    ) {
        self.rows.push(Row::new(
            self.case,
            check,
            self.method,
            self.dt,
            value,
            expected,
            tolerance,
            comparison,
            reason,
        ));
    }
}
