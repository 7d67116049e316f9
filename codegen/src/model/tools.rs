//! The derivation tools of the model: initial conditions, linear solves, coefficients,
//! substitution, and recording the formulas the runtime uses. The model statement itself (the
//! named pieces of the equations of motion) is in `mod.rs`.

use std::collections::HashMap;

use super::{Model, Rates, Vec2};
use crate::derive::{derivative, partial, solve_linear};
use crate::expr::{ExprId, Symbol};
use crate::ir::{Formula, Output};

impl Model {
    /// Initial-condition equations of a trajectory `q` at its start: q_i(0) = `start[i].0` and
    /// q_i'(0) = `start[i].1` (names of input symbols), where `at_start` substitutes the start
    /// values of the time-dependent symbols. Equations come position then velocity per component.
    pub(crate) fn initial_conditions(
        &mut self,
        q: Vec2,
        rates: &Rates,
        at_start: &[(&str, ExprId)],
        start: [(&str, &str); 2],
    ) -> Vec<ExprId> {
        let mut eqs = Vec::with_capacity(4);
        for (qi, (pos, vel)) in q.into_iter().zip(start) {
            let dq = derivative(&mut self.graph, qi, rates);
            let (pos, vel) = (self.var(pos), self.var(vel));
            let e = self.graph.sub(qi, pos);
            eqs.push(self.subst(e, at_start));
            let e = self.graph.sub(dq, vel);
            eqs.push(self.subst(e, at_start));
        }
        eqs
    }

    /// Solve the equations for the named unknowns.
    pub(crate) fn solve(&mut self, equations: &[ExprId], unknowns: &[&str]) -> Vec<ExprId> {
        let syms: Vec<Symbol> = unknowns.iter().map(|u| self.graph.symbol(u)).collect();
        solve_linear(&mut self.graph, equations, &syms).expect("the model's systems are solvable")
    }

    /// The coefficients of `e` with respect to symbols in which it is linear, by partial
    /// differentiation.
    pub(crate) fn coefficients(&mut self, e: ExprId, of: &[ExprId]) -> Vec<ExprId> {
        of.iter()
            .map(|&s| {
                let sym = self.graph.as_symbol(s).expect("coefficients of symbols");
                partial(&mut self.graph, e, sym)
            })
            .collect()
    }

    /// Substitute symbols (by name) with expressions.
    pub(crate) fn subst(&mut self, e: ExprId, pairs: &[(&str, ExprId)]) -> ExprId {
        let map: HashMap<Symbol, ExprId> = pairs
            .iter()
            .map(|&(n, v)| (self.graph.symbol(n), v))
            .collect();
        self.graph.substitute(e, &map)
    }

    /// Record a formula used by the runtime. Its inputs are the declared structs of the symbols
    /// its outputs use.
    pub(crate) fn add_formula(
        &mut self,
        name: &str,
        summary: &str,
        source: &str,
        derivation: &str,
        output_type: &str,
        outputs: Vec<(&str, &str, ExprId)>,
    ) {
        self.push_formula(
            name,
            [summary, source, derivation],
            output_type,
            outputs,
            false,
        );
    }

    /// Record a formula only the verification tests use (emitted `#[doc(hidden)]`).
    pub(crate) fn add_test_formula(
        &mut self,
        name: &str,
        summary: &str,
        source: &str,
        derivation: &str,
        output_type: &str,
        outputs: Vec<(&str, &str, ExprId)>,
    ) {
        self.push_formula(
            name,
            [summary, source, derivation],
            output_type,
            outputs,
            true,
        );
    }

    fn push_formula(
        &mut self,
        name: &str,
        [summary, source, derivation]: [&str; 3],
        output_type: &str,
        outputs: Vec<(&str, &str, ExprId)>,
        test_only: bool,
    ) {
        let outputs = outputs
            .into_iter()
            .map(|(name, doc, expr)| Output {
                name: name.to_owned(),
                doc: doc.to_owned(),
                expr,
            })
            .collect();
        self.formulas.push(Formula {
            name: name.to_owned(),
            summary: summary.to_owned(),
            source: source.to_owned(),
            derivation: derivation.to_owned(),
            test_only,
            output_type: output_type.to_owned(),
            outputs,
        });
    }
}
