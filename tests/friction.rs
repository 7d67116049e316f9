//! Coulomb friction (issue 12, `docs/MODEL.md` §10) checked against an independent oracle
//! (`friction/oracle.rs`): every method on the cases, event by event.

mod friction {
    pub mod agreement;
    pub mod oracle;
    pub mod properties;
}
