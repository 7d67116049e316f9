//! Periodic orbits (`rotor_rub::orbit`, issue 30, `docs/MODEL.md` §18), per call, on three
//! period-1 orbits of the `paper` preset found by shooting first:
//!
//! * `free` (η = 0.5): no contact, the map is the closed form alone;
//! * `rub` (η = 3.0): four switches per period (two contacts);
//! * `annular` (η = 2.2): the full annular rub, contact all period long.
//!
//! `orbit/map/<orbit>`: one forcing period of the stroboscopic map without the monodromy matrix
//! (hybrid, tol 1e-12, the shooting's default trajectory); `orbit/map_monodromy/<orbit>`: the
//! same with the monodromy (free flight's closed-form transition matrices, DOP853 on the 20
//! variational states in contact at tol 1e-11, saltation at the switches); `orbit/shoot/<orbit>`:
//! Newton from the orbit's state moved by 1e-2 in each component to the default residual 1e-10.

mod common;

use std::hint::black_box;

use rotor_rub::orbit::{MapSettings, ShootingSettings, shoot, stroboscopic_map};
use rotor_rub::{Preset, State};

/// (name, η, a guess the orbit is found from).
const ORBITS: [(&str, f64, [f64; 4]); 3] = [
    ("free", 0.5, [0.0, 0.0, 0.0, 0.0]),
    ("rub", 3.0, [0.0951, 0.3954, 2.4799, 2.5507]),
    ("annular", 2.2, [2.1102, -1.1918, 0.4670, -5.6431]),
];

fn main() {
    let mut c = common::criterion();
    for (name, eta, guess) in ORBITS {
        let mut params = Preset::Paper.problem().params;
        params.speed_ratio = eta;
        let [x, y, vx, vy] = guess;
        let settings = ShootingSettings::default();
        let orbit = shoot(&params, State::new(x, y, vx, vy), 1, &settings)
            .expect("the orbit is found")
            .orbit;
        let s = orbit.state;
        let plain = MapSettings {
            jacobian: false,
            ..MapSettings::default()
        };
        let full = MapSettings::default();
        c.bench_function(&format!("orbit/map/{name}"), |b| {
            b.iter(|| stroboscopic_map(&params, black_box(s), 1, &plain, &mut ()))
        });
        c.bench_function(&format!("orbit/map_monodromy/{name}"), |b| {
            b.iter(|| stroboscopic_map(&params, black_box(s), 1, &full, &mut ()))
        });
        let off = State::new(s.x + 1e-2, s.y + 1e-2, s.vx + 1e-2, s.vy + 1e-2);
        let shot = shoot(&params, off, 1, &settings).expect("found again");
        eprintln!(
            "{name} (eta = {eta}): multipliers' largest modulus {:.4}, Newton from 1e-2 off: {} maps, residuals {:?}",
            orbit.spectral_radius(),
            shot.evaluations,
            shot.residuals()
        );
        c.bench_function(&format!("orbit/shoot/{name}"), |b| {
            b.iter(|| shoot(&params, black_box(off), 1, &settings))
        });
    }
    c.final_summary();
}
