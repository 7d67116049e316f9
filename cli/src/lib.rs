//! The library behind the `rotor-rub` command: building problems from presets, config files and
//! overrides, method options, trajectory passes, analyses (Poincaré sections, spectra, response
//! classes, sweeps), output files and plots. The binary (`main.rs`) parses the command line and
//! dispatches; the Python package (`python/`) calls the same functions, so both give the same
//! results and the same error messages.
//!
//! Commands: `fig2` (the main job), `simulate`, `compare`, `sweep` and `merge` (shards with
//! metadata, `shard`), `poincare`, `spectrum`, `friction_fig`, `runup` (the speed program from a
//! preset, options or a profile CSV; per-period and event files; jumps and hysteresis), `orbit`
//! and `continue` (`orbit/`: periodic orbits, branches by pseudo-arclength continuation,
//! bifurcations located), `params`, `presets`; `model_file` (rotors from matrices:
//! `check-model`, `simulate --model`, and the stator ring with mass that `simulate` runs when
//! `stator_mass_ratio` > 0). Shared: `problem` (presets, TOML configs,
//! `--set`), `options`, `trajectory`
//! (passes over a run), `analysis` (response classes, Lyapunov exponents, spectra, switch
//! counts), `plot`. Files and streams: `stdio` is the one writer to stdout and stderr (a closed
//! pipe ends quietly, exit 141; `.ci/run` refuses a print anywhere else); `output` writes each
//! file to a temporary and moves it into place only when complete (regular files replaced,
//! devices and FIFOs written through), refuses an output that is another output or an input,
//! and removes temporaries on SIGINT/SIGTERM/SIGHUP (exit 128 + the signal); `limits` caps
//! counts by memory (physical, cgroup, `ulimit`) and runs by `--max-work`; `watch` lets a caller
//! stop a run (Ctrl-C in Python) and see its progress without changing its trajectory.

pub mod analysis;
pub mod compare;
pub mod error;
pub mod fig2;
pub mod friction_fig;
pub mod limits;
pub mod merge;
pub mod model_file;
pub mod options;
pub mod orbit;
pub mod output;
pub mod params;
pub mod plot;
pub mod poincare;
pub mod presets;
pub mod problem;
pub mod runup;
pub mod shard;
pub mod simulate;
pub mod spectrum;
pub mod stdio;
pub mod sweep;
pub mod trajectory;
pub mod watch;
