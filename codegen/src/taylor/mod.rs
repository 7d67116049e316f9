//! Taylor-coefficient recurrences (automatic differentiation of Taylor series) of a regime's
//! field, for the `taylor` method's contact segments (`docs/MODEL.md` §16).
//!
//! A [`System`] names the states of an autonomous ODE with their rates (expressions of the
//! model's graph) and the observed quantities the runtime needs as polynomials (the switch
//! functions). [`decompose`] turns the DAG into a list of elementary operations on truncated
//! series, each operand an earlier series:
//!
//! * `Linear`: a sum of series with time-constant coefficients (plus a constant at order 0);
//! * `Product`, `Square`: Cauchy products;
//! * `Power` (integer exponent p, p = −1 the reciprocal), `HalfPower` (a^(k/2), an integer
//!   power of a square root) and `Sqrt`: the recurrences from a·r' = p a'·r and r² = a.
//!
//! Every sub-expression that does not change in time (parameters, 2ν, μσ, …) becomes one entry of
//! a constants formula, emitted through the ordinary formula emitter (CSE, typed input structs);
//! [`emit`] writes the recurrences as straight-line code over the operations, one
//! function for order 0 and one for any order n ≥ 1, calling the runtime's series kernels
//! (`crate::taylor::kernels`, `ts::…`). A time-dependent call other than the square root fails
//! the build naming the system.

pub mod emit;

use std::collections::HashMap;

use crate::expr::{ExprId, Func, Graph, Node, Symbol};

use crate::ir::System;

/// A coefficient of a linear combination: a literal or a time-constant expression.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Coef {
    /// A number.
    Literal(f64),
    /// Entry k of the system's constants.
    Constant(usize),
}

/// One elementary operation: the series it defines in terms of earlier series (by index).
#[derive(Clone, Debug, PartialEq)]
pub enum Op {
    /// A state: order 0 given by the caller, order n + 1 = (rate)_n / (n + 1).
    State,
    /// `constant + Σ coef·series` (the constant enters order 0 only).
    Linear {
        /// The time-constant term, if any.
        constant: Option<Coef>,
        /// The time-dependent terms.
        terms: Vec<(Coef, usize)>,
    },
    /// The product of two different series.
    Product(usize, usize),
    /// The square of a series.
    Square(usize),
    /// An integer power (≠ 0, 1, 2) of a series whose order-0 coefficient is non-zero.
    Power(usize, i32),
    /// The square root of a series whose order-0 coefficient is positive.
    Sqrt(usize),
    /// A half-integer power a^(k/2) (k odd) of a series whose order-0 coefficient is positive:
    /// an integer power of a square root, in one recurrence (`1/√a` is one convolution, where
    /// the square root and then its reciprocal are two, one after the other).
    HalfPower(usize, i32),
}

/// A system decomposed into elementary operations.
pub struct Program {
    /// The time-constant sub-expressions, in order of first use (the constants formula).
    pub constants: Vec<ExprId>,
    /// The operations; the first `states` are the states, each op refers to earlier ones only.
    pub ops: Vec<Op>,
    /// Number of states (the first ops).
    pub states: usize,
    /// The series index of each state's rate.
    pub rates: Vec<usize>,
    /// The series index of each observed quantity.
    pub observed: Vec<usize>,
}

struct Decomposer<'a> {
    g: &'a mut Graph,
    system: String,
    states: HashMap<Symbol, usize>,
    varying: HashMap<ExprId, bool>,
    series: HashMap<ExprId, usize>,
    products: HashMap<(usize, usize), usize>,
    constants: Vec<ExprId>,
    constant_index: HashMap<ExprId, usize>,
    ops: Vec<Op>,
}

impl Decomposer<'_> {
    /// Whether `id` changes in time (depends on a state).
    fn varying(&mut self, id: ExprId) -> bool {
        if let Some(&v) = self.varying.get(&id) {
            return v;
        }
        let v = match self.g.node(id).clone() {
            Node::Const(_) => false,
            Node::Input(s) => self.states.contains_key(&s),
            _ => self.g.children(id).into_iter().any(|c| self.varying(c)),
        };
        self.varying.insert(id, v);
        v
    }

    fn coef(&mut self, id: ExprId) -> Coef {
        if let Some(c) = self.g.as_const(id) {
            return Coef::Literal(c);
        }
        let next = self.constants.len();
        let k = *self.constant_index.entry(id).or_insert(next);
        if k == next {
            self.constants.push(id);
        }
        Coef::Constant(k)
    }

    fn push(&mut self, op: Op) -> usize {
        self.ops.push(op);
        self.ops.len() - 1
    }

    /// The series of the product of time-dependent factors (sorted ids), left to right.
    fn product_of(&mut self, factors: &[ExprId]) -> usize {
        let mut acc = self.series(factors[0]);
        for &f in &factors[1..] {
            let b = self.series(f);
            let key = (acc.min(b), acc.max(b));
            acc = match self.products.get(&key) {
                Some(&i) => i,
                None => {
                    let op = if key.0 == key.1 {
                        Op::Square(key.0)
                    } else {
                        Op::Product(key.0, key.1)
                    };
                    let i = self.push(op);
                    self.products.insert(key, i);
                    i
                }
            };
        }
        acc
    }

    /// A term as (time-constant coefficient, series).
    fn term(&mut self, id: ExprId) -> (Coef, usize) {
        if let Node::Mul(fs) = self.g.node(id).clone() {
            let (vary, fixed): (Vec<ExprId>, Vec<ExprId>) =
                fs.into_iter().partition(|&f| self.varying(f));
            let c = self.g.product(&fixed);
            let c = self.coef(c);
            let s = self.product_of(&vary);
            return (c, s);
        }
        (Coef::Literal(1.0), self.series(id))
    }

    /// The series index of the time-dependent expression `id`.
    fn series(&mut self, id: ExprId) -> usize {
        if let Some(&i) = self.series.get(&id) {
            return i;
        }
        let i = match self.g.node(id).clone() {
            Node::Input(s) => self.states[&s],
            Node::Add(ts) => {
                let (vary, fixed): (Vec<ExprId>, Vec<ExprId>) =
                    ts.into_iter().partition(|&t| self.varying(t));
                let constant = if fixed.is_empty() {
                    None
                } else {
                    let c = self.g.sum(&fixed);
                    Some(self.coef(c))
                };
                let terms = vary.into_iter().map(|t| self.term(t)).collect();
                self.push(Op::Linear { constant, terms })
            }
            Node::Mul(_) => match self.term(id) {
                (Coef::Literal(1.0), s) => s,
                (c, s) => self.push(Op::Linear {
                    constant: None,
                    terms: vec![(c, s)],
                }),
            },
            Node::Pow(b, 2) => {
                let b = self.series(b);
                self.product_of_pair(b)
            }
            Node::Pow(b, n) => match self.g.node(b).clone() {
                // (√a)^n: one recurrence on a, not the root's series and then its power.
                Node::Call(Func::Sqrt, a) if n % 2 != 0 => {
                    let a = self.series(a);
                    self.push(Op::HalfPower(a, n))
                }
                _ => {
                    let b = self.series(b);
                    self.push(Op::Power(b, n))
                }
            },
            Node::Call(Func::Sqrt, a) => {
                let a = self.series(a);
                self.push(Op::Sqrt(a))
            }
            Node::Call(f, _) => panic!(
                "Taylor system `{}`: the time-dependent call {}(…) has no recurrence; carry it as a state (as the forcing phasor is)",
                self.system,
                f.name()
            ),
            Node::Const(_) => unreachable!("constants are not series"),
        };
        self.series.insert(id, i);
        i
    }

    fn product_of_pair(&mut self, b: usize) -> usize {
        if let Some(&i) = self.products.get(&(b, b)) {
            return i;
        }
        let i = self.push(Op::Square(b));
        self.products.insert((b, b), i);
        i
    }

    /// A series for `id`, constant or not (a constant becomes a `Linear` with no terms).
    fn any(&mut self, id: ExprId) -> usize {
        if self.varying(id) {
            self.series(id)
        } else {
            let c = self.coef(id);
            self.push(Op::Linear {
                constant: Some(c),
                terms: Vec::new(),
            })
        }
    }
}

/// Decompose `system` into elementary series operations.
pub fn decompose(g: &mut Graph, system: &System) -> Program {
    let states: HashMap<Symbol, usize> = system
        .states
        .iter()
        .enumerate()
        .map(|(i, &(s, _))| (s, i))
        .collect();
    let mut d = Decomposer {
        g,
        system: system.name.clone(),
        states,
        varying: HashMap::new(),
        series: HashMap::new(),
        products: HashMap::new(),
        constants: Vec::new(),
        constant_index: HashMap::new(),
        ops: vec![Op::State; system.states.len()],
    };
    let rates = system.states.iter().map(|&(_, r)| d.any(r)).collect();
    let observed = system.observed.iter().map(|(_, _, e)| d.any(*e)).collect();
    Program {
        constants: d.constants,
        ops: d.ops,
        states: system.states.len(),
        rates,
        observed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn system(g: &mut Graph, rate: impl Fn(&mut Graph, ExprId, ExprId) -> ExprId) -> System {
        let (x, y) = (g.input("x"), g.input("y"));
        let r = rate(g, x, y);
        System {
            name: "test".to_owned(),
            summary: String::new(),
            source: String::new(),
            states: vec![(g.symbol("x"), y), (g.symbol("y"), r)],
            observed: Vec::new(),
        }
    }

    #[test]
    fn shared_products_are_one_operation_and_constants_are_hoisted() {
        let mut g = Graph::new();
        // y' = k·x·y + x·y/√x: x·y once, k once, the square root and the power once each.
        let s = system(&mut g, |g, x, y| {
            let k = g.input("k");
            let xy = g.mul(x, y);
            let a = g.mul(k, xy);
            let r = g.sqrt(x);
            let b = g.div(xy, r);
            g.add(a, b)
        });
        let p = decompose(&mut g, &s);
        let count = |f: &dyn Fn(&Op) -> bool| p.ops.iter().filter(|o| f(o)).count();
        assert_eq!(count(&|o| matches!(o, Op::Product(..))), 2, "{:?}", p.ops);
        // 1/√x: one half power, no square root and no reciprocal.
        assert_eq!(count(&|o| matches!(o, Op::HalfPower(_, -1))), 1);
        assert_eq!(count(&|o| matches!(o, Op::Sqrt(_) | Op::Power(..))), 0);
        assert_eq!(p.constants.len(), 1, "k");
        assert_eq!(p.states, 2);
        // Every operation refers to earlier series only.
        for (i, op) in p.ops.iter().enumerate() {
            let refs: Vec<usize> = match op {
                Op::State => vec![],
                Op::Linear { terms, .. } => terms.iter().map(|t| t.1).collect(),
                Op::Product(a, b) => vec![*a, *b],
                Op::Square(a) | Op::Power(a, _) | Op::Sqrt(a) | Op::HalfPower(a, _) => vec![*a],
            };
            assert!(
                refs.iter().all(|&r| r < i || matches!(op, Op::State)),
                "{i}: {op:?}"
            );
        }
    }

    #[test]
    #[should_panic(expected = "has no recurrence")]
    fn a_time_dependent_call_without_recurrence_fails_the_build() {
        let mut g = Graph::new();
        let s = system(&mut g, |g, x, _| g.sin(x));
        decompose(&mut g, &s);
    }
}
