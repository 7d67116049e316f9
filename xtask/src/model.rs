//! `cargo xtask fmu --model FILE`: the model file read by the CLI's reader
//! (`rotor_rub_cli::model_file::load`, the one reader), checked and stated at its running speed
//! as the CLI states it, then handed to the FMU as its resource
//! (`rotor_rub_fmu::file::FileModel`, SI).

use std::path::Path;

use rotor_rub_cli::model_file::{Key, ModelSpec, load, on_large_stack};
use rotor_rub_fmu::file::{FileModel, FileUnbalance, MAX_DOFS};

/// Read and check `path`: the FMU's statement of it.
///
/// # Errors
/// What the reader or the runtime refuses (the CLI's messages, naming the key), or a model of
/// more than [`MAX_DOFS`] degrees of freedom.
pub fn read(path: &Path) -> Result<FileModel, String> {
    // The reader's messages name the file already.
    let spec = load(path)?;
    file_model(&spec).map_err(|e| format!("{}: {e}", path.display()))
}

/// The FMU's statement of a model file already read: its matrices at the running speed (C and
/// K interpolated as the CLI does when the file lists speed-dependent ones), every value in SI.
///
/// # Errors
/// More than [`MAX_DOFS`] degrees of freedom, or what the runtime refuses in the statement.
pub fn file_model(spec: &ModelSpec) -> Result<FileModel, String> {
    let n = spec.dofs();
    if n > MAX_DOFS {
        return Err(format!(
            "the model has {n} degrees of freedom ({}): the FMU holds at most {MAX_DOFS} (first-order capacity {}); reduce the model (e.g. to its lowest modes) or run it with rotor-rub simulate --model",
            spec.dofs.join(", "),
            2 * MAX_DOFS
        ));
    }
    // Every check the CLI makes (M symmetric positive definite, the station's DOFs, …), with its
    // messages.
    let checked = spec.clone();
    on_large_stack(move || checked.build().map(drop)).map_err(|e| e.to_string())?;
    let (damping, stiffness) = spec
        .matrices_at(Key::Speed, spec.speed)
        .map_err(|e| e.to_string())?;
    let flat = |m: &rotor_rub_cli::model_file::Dense| {
        (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| m.get(i, j))
            .collect::<Vec<f64>>()
    };
    let r = &spec.rub;
    let zeros = vec![0.0; n];
    Ok(FileModel {
        name: spec.name.clone(),
        dofs: spec.dofs.clone(),
        mass: flat(&spec.mass),
        damping: flat(&damping),
        gyroscopic: flat(&spec.gyroscopic),
        stiffness: flat(&stiffness),
        speed: spec.speed,
        phase: spec.phase,
        unbalances: spec
            .unbalances
            .iter()
            .map(|u| FileUnbalance {
                dof_x: u.dof_x,
                dof_y: u.dof_y,
                m_e: u.m_e,
                phase: u.phase,
            })
            .collect(),
        force: if spec.force.is_empty() {
            zeros.clone()
        } else {
            spec.force.clone()
        },
        rub: (r.dof_x, r.dof_y),
        stator: r.stator,
        clearance: r.clearance,
        contact_stiffness: r.contact_stiffness,
        friction_coefficient: r.friction_coefficient,
        radius: r.radius,
        offset: r.offset,
        initial: spec
            .initial
            .clone()
            .unwrap_or_else(|| (zeros.clone(), zeros)),
    })
}
