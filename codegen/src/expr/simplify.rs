//! Simplifying constructors for sums, products, powers and calls.
//!
//! Rules, all value-preserving for finite inputs (integer powers, principal square roots):
//! - constant folding (sqrt, and exp/sin/cos only where the result is exact, so that no host
//!   `libm` value is baked into code that the runtime evaluates with its own `libm`);
//! - neutral and absorbing elements (`a + 0`, `a · 1`, `a · 0`, `a^1`, `a^0`);
//! - flattening of nested sums and products, operands sorted so equal sums intern equally;
//! - like-term collection `2a + 3a → 5a` and like-factor collection `a · a⁻¹ → 1`, `a·a → a²`;
//! - a constant times a sum stays factored (`2a + 3a → 5a` for a sum `a` too, and `a/a → 1`);
//! - `(a^m)^n → a^(mn)`, `(a·b)^n → aⁿ·bⁿ`, `sqrt(a)^(2k) → a^k`.

use std::collections::BTreeMap;

use super::{ExprId, Func, Graph, Node};

impl Graph {
    /// The simplified sum of `terms`.
    ///
    /// Terms are first grouped by their non-constant part, sums taken as units, so
    /// `2a + 3a → 5a` and `a − a → 0` for any `a`. If more than one group remains, sums are
    /// expanded into their terms (scaled by their coefficient) and collected again, so terms
    /// inside them can meet: `a + (a + b) → 2a + b`.
    pub fn sum(&mut self, terms: &[ExprId]) -> ExprId {
        let (constant, groups) = self.collect_terms(terms);
        if constant == 0.0 && groups.len() == 1 {
            let (rest, c) = groups[0];
            return if c == 1.0 {
                rest
            } else {
                self.scaled_term(c, rest)
            };
        }
        if groups
            .iter()
            .any(|&(rest, _)| matches!(self.node(rest), Node::Add(_)))
        {
            let mut flat = Vec::new();
            if constant != 0.0 {
                flat.push(self.constant(constant));
            }
            for (rest, c) in groups {
                match self.node(rest).clone() {
                    Node::Add(ts) => flat.extend(ts.into_iter().map(|u| self.scale(c, u))),
                    _ => flat.push(if c == 1.0 {
                        rest
                    } else {
                        self.scaled_term(c, rest)
                    }),
                }
            }
            return self.sum(&flat);
        }
        let mut out = Vec::new();
        if constant != 0.0 {
            out.push(self.constant(constant));
        }
        for (rest, c) in groups {
            out.push(if c == 1.0 {
                rest
            } else {
                self.scaled_term(c, rest)
            });
        }
        match out.len() {
            0 => self.constant(0.0),
            1 => out[0],
            _ => {
                out.sort();
                self.intern(Node::Add(out))
            }
        }
    }

    /// The constant part of `terms` and their other parts with summed coefficients (zero
    /// coefficients dropped), in id order.
    fn collect_terms(&mut self, terms: &[ExprId]) -> (f64, Vec<(ExprId, f64)>) {
        let mut constant = 0.0;
        let mut groups: BTreeMap<ExprId, f64> = BTreeMap::new();
        for &t in terms {
            match self.split_coefficient(t) {
                (c, None) => constant += c,
                (c, Some(r)) => *groups.entry(r).or_insert(0.0) += c,
            }
        }
        (
            constant,
            groups.into_iter().filter(|&(_, c)| c != 0.0).collect(),
        )
    }

    /// `c · rest` as a product node without re-distributing over sums.
    fn scaled_term(&mut self, c: f64, rest: ExprId) -> ExprId {
        let k = self.constant(c);
        let mut fs = vec![k];
        match self.node(rest) {
            Node::Mul(inner) => fs.extend(inner.iter().copied()),
            _ => fs.push(rest),
        }
        fs.sort();
        self.intern(Node::Mul(fs))
    }

    /// Split a term into its constant coefficient and the rest (`None` for a pure constant).
    fn split_coefficient(&mut self, t: ExprId) -> (f64, Option<ExprId>) {
        match self.node(t).clone() {
            Node::Const(bits) => (f64::from_bits(bits), None),
            Node::Mul(fs) => {
                let mut c = 1.0;
                let mut rest = Vec::new();
                for f in fs {
                    match self.as_const(f) {
                        Some(v) => c *= v,
                        None => rest.push(f),
                    }
                }
                let r = match rest.len() {
                    0 => return (c, None),
                    1 => rest[0],
                    _ => self.intern(Node::Mul(rest)),
                };
                (c, Some(r))
            }
            _ => (1.0, Some(t)),
        }
    }

    /// The simplified product of `factors`.
    pub fn product(&mut self, factors: &[ExprId]) -> ExprId {
        let mut flat = Vec::with_capacity(factors.len());
        for &f in factors {
            match self.node(f) {
                Node::Mul(fs) => flat.extend(fs.iter().copied()),
                _ => flat.push(f),
            }
        }
        let mut constant = 1.0;
        let mut powers: BTreeMap<ExprId, i32> = BTreeMap::new();
        for f in flat {
            match self.node(f).clone() {
                Node::Const(bits) => constant *= f64::from_bits(bits),
                Node::Pow(b, n) => *powers.entry(b).or_insert(0) += n,
                _ => *powers.entry(f).or_insert(0) += 1,
            }
        }
        if constant == 0.0 {
            return self.constant(0.0);
        }
        let mut out = Vec::new();
        for (base, n) in powers {
            if n != 0 {
                out.push(self.powi(base, n));
            }
        }
        if out.is_empty() {
            return self.constant(constant);
        }
        // A power can fold into a product or a constant (sqrt(a·b)² → a·b, (3a)² → 9a²):
        // collect again so products stay flat and like factors meet.
        if out
            .iter()
            .any(|&f| matches!(self.node(f), Node::Mul(_) | Node::Const(_)))
        {
            out.push(self.constant(constant));
            return self.product(&out);
        }
        if constant != 1.0 {
            out.push(self.constant(constant));
        }
        if out.len() == 1 {
            return out[0];
        }
        out.sort();
        self.intern(Node::Mul(out))
    }

    /// The simplified integer power `base^n`.
    pub fn powi(&mut self, base: ExprId, n: i32) -> ExprId {
        if n == 0 {
            return self.constant(1.0);
        }
        if n == 1 {
            return base;
        }
        match self.node(base).clone() {
            Node::Const(bits) => {
                let v = f64::from_bits(bits);
                if v != 0.0 || n > 0 {
                    return self.constant(v.powi(n));
                }
            }
            Node::Pow(b, m) => return self.powi(b, m * n),
            Node::Mul(fs) => {
                let ps: Vec<_> = fs.iter().map(|&f| self.powi(f, n)).collect();
                return self.product(&ps);
            }
            Node::Call(Func::Sqrt, a) if n % 2 == 0 => return self.powi(a, n / 2),
            _ => {}
        }
        self.intern(Node::Pow(base, n))
    }

    /// The simplified call `f(arg)`.
    pub fn call(&mut self, f: Func, arg: ExprId) -> ExprId {
        if let Some(v) = self.as_const(arg) {
            let exact = match f {
                Func::Sqrt => v >= 0.0,
                Func::Exp | Func::Sin | Func::Cos => v == 0.0,
            };
            if exact {
                return self.constant(f.apply(v));
            }
        }
        self.intern(Node::Call(f, arg))
    }
}
