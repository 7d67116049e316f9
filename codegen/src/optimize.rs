//! Common-subexpression elimination into straight-line code, and operation counts.
//!
//! Interning already shares every repeated sub-expression; CSE decides which shared nodes get a
//! `let` binding (every non-leaf node used twice or more, and every base of a power that is
//! emitted as repeated multiplication) and orders the bindings topologically.

use std::collections::{BTreeSet, HashMap};
use std::fmt;
use std::ops::AddAssign;

use crate::expr::{ExprId, Func, Graph, Node};

/// Arithmetic operation counts of emitted code.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCounts {
    /// Additions and subtractions.
    pub add: u64,
    /// Multiplications.
    pub mul: u64,
    /// Divisions.
    pub div: u64,
    /// Square roots.
    pub sqrt: u64,
    /// exp, sin and cos calls.
    pub transcendental: u64,
}

impl AddAssign for OpCounts {
    fn add_assign(&mut self, o: Self) {
        self.add = self.add.saturating_add(o.add);
        self.mul = self.mul.saturating_add(o.mul);
        self.div = self.div.saturating_add(o.div);
        self.sqrt = self.sqrt.saturating_add(o.sqrt);
        self.transcendental = self.transcendental.saturating_add(o.transcendental);
    }
}

impl fmt::Display for OpCounts {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:>5} add {:>5} mul {:>4} div {:>3} sqrt {:>3} trans",
            self.add, self.mul, self.div, self.sqrt, self.transcendental
        )
    }
}

/// The straight-line plan of one function: bindings in evaluation order.
pub struct Plan {
    /// Nodes bound by `let`, in evaluation order.
    pub bindings: Vec<ExprId>,
    /// Binding index of each bound node.
    pub temp_index: HashMap<ExprId, usize>,
    /// Operation counts if every output were evaluated as a tree (no sharing).
    pub before: OpCounts,
}

/// Plan the evaluation of `outputs`.
pub fn plan(g: &Graph, outputs: &[ExprId]) -> Plan {
    let mut uses: HashMap<ExprId, usize> = HashMap::new();
    let mut forced: BTreeSet<ExprId> = BTreeSet::new();
    let mut order = Vec::new();
    let mut visited = BTreeSet::new();
    for &o in outputs {
        *uses.entry(o).or_insert(0) += 1;
        visit(g, o, &mut uses, &mut forced, &mut visited, &mut order);
    }
    let is_leaf = |id: ExprId| matches!(g.node(id), Node::Const(_) | Node::Input(_));
    let bindings: Vec<ExprId> = order
        .iter()
        .copied()
        .filter(|&id| !is_leaf(id) && (uses[&id] >= 2 || forced.contains(&id)))
        .collect();
    let temp_index = bindings
        .iter()
        .enumerate()
        .map(|(k, &id)| (id, k))
        .collect();
    let mut memo = HashMap::new();
    let mut before = OpCounts::default();
    for &o in outputs {
        before += tree_ops(g, o, &mut memo);
    }
    Plan {
        bindings,
        temp_index,
        before,
    }
}

fn visit(
    g: &Graph,
    id: ExprId,
    uses: &mut HashMap<ExprId, usize>,
    forced: &mut BTreeSet<ExprId>,
    visited: &mut BTreeSet<ExprId>,
    order: &mut Vec<ExprId>,
) {
    if !visited.insert(id) {
        return;
    }
    for c in g.children(id) {
        *uses.entry(c).or_insert(0) += 1;
        if matches!(g.node(id), Node::Pow(_, n) if n.abs() >= 2) {
            forced.insert(c);
        }
        visit(g, c, uses, forced, visited, order);
    }
    order.push(id);
}

/// Operations of `id` evaluated as a tree (no sharing), as the emitter would write it with no
/// bindings: a power's base is repeated, a product's factors multiplied and divided.
fn tree_ops(g: &Graph, id: ExprId, memo: &mut HashMap<ExprId, OpCounts>) -> OpCounts {
    if let Some(&c) = memo.get(&id) {
        return c;
    }
    let mut c = OpCounts::default();
    match g.node(id).clone() {
        Node::Const(_) | Node::Input(_) => {}
        Node::Add(ts) => {
            c.add = ts.len() as u64 - 1;
            for t in ts {
                c += tree_ops(g, t, memo);
            }
        }
        Node::Mul(fs) => {
            let (mut num, mut den) = (0u64, 0u64);
            for f in fs {
                match g.node(f).clone() {
                    Node::Const(bits) => num += u64::from(f64::from_bits(bits).abs() != 1.0),
                    Node::Pow(b, n) => {
                        let k = u64::from(n.unsigned_abs());
                        if n < 0 {
                            den += k
                        } else {
                            num += k
                        }
                        let base = tree_ops(g, b, memo);
                        for _ in 0..k {
                            c += base;
                        }
                    }
                    _ => {
                        num += 1;
                        c += tree_ops(g, f, memo);
                    }
                }
            }
            c.mul += num.saturating_sub(1) + den.saturating_sub(1);
            c.div += u64::from(den > 0);
        }
        Node::Pow(b, n) => {
            let k = u64::from(n.unsigned_abs());
            c.mul = k - 1;
            c.div = u64::from(n < 0);
            let base = tree_ops(g, b, memo);
            for _ in 0..k {
                c += base;
            }
        }
        Node::Call(f, a) => {
            if f == Func::Sqrt {
                c.sqrt = 1
            } else {
                c.transcendental = 1
            }
            c += tree_ops(g, a, memo);
        }
    }
    memo.insert(id, c);
    c
}
