use rotor_rub::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let eta: f64 = args.get(1).map(|s| s.parse().unwrap()).unwrap_or(1.5);
    let method = args
        .get(2)
        .map(|s| Method::from_name(s).unwrap())
        .unwrap_or(Method::Analytic);
    let tol: f64 = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(1e-10);
    let periods: f64 = args.get(4).map(|s| s.parse().unwrap()).unwrap_or(100.0);
    let mut pb = Preset::Paper.problem();
    pb.params.speed_ratio = eta;
    if args.get(5).is_some() {
        pb.params.offset_x = 0.0;
        pb.params.offset_y = 0.0;
    }
    let opts = Options {
        tol: Some(tol),
        ..Options::with_method(method)
    };
    let t = std::time::Instant::now();
    let mut p = Propagator::new(&pb, &opts).unwrap();
    let t_end = periods * pb.params.forcing_period();
    let evs: Vec<Event> = events(&mut p, t_end).collect::<Result<_, _>>().unwrap();
    println!(
        "{:?} switches {} first {:.12} last {:.12} in {:?}",
        method,
        evs.len(),
        evs[1].time,
        evs[evs.len().min(20) - 1].time,
        t.elapsed()
    );
}
