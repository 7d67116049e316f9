/* The paper preset for 100 forcing periods in fixed steps dt = 1e-3 through the C ABI: collects
 * the contact switch times and prints them, with a checkpoint state every 1000 steps.
 *
 * `paper control KP KD` runs the same fixed-rate loop with a controller, as a rig would: each
 * cycle measures the state of the last step, computes a PD force towards the stator centre,
 * f = -KP (q - offset) - KD q', applies it for the next step (rotor_rub_stepper_set_input_force),
 * and steps with a hard work budget (on_cap = FAIL: a step that would exceed its bounded work is
 * refused and retried as two half steps instead of overrunning).
 *
 * Build (after `cargo build -p rotor-rub-ffi`, from the repository root; the library sits in
 * the target directory's profile folder):
 *   cc -O2 -Iffi/include ffi/examples/paper.c target/debug/librotor_rub_ffi.a \
 *      -lgcc_s -lutil -lrt -lpthread -lm -ldl -lc -o paper
 * (`rustc --print native-static-libs` lists the system libraries Rust's std needs.)
 *
 * Output lines (numbers with 17 significant digits):
 *   state <step> <time> <x> <y> <vx> <vy> <regime>     every CHECK_EVERY steps
 *   switch <index> <enter|exit> <time> <x> <y> <vx> <vy>
 *   summary <steps> <switches> <dropped> <capped steps> <steps split for the budget>
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rotor_rub.h"

#define MAX_SWITCHES 8192
#define CHECK_EVERY 1000L
#define PERIODS 100.0

static double switch_time[MAX_SWITCHES];
static int32_t switch_kind[MAX_SWITCHES];
static RotorRubState switch_state[MAX_SWITCHES];

static int fail(const char *what, int32_t code) {
    fprintf(stderr, "%s: %s (code %d)\n", what, rotor_rub_error_message(code), (int)code);
    return 1;
}

int main(int argc, char **argv) {
    int control = argc >= 4 && strcmp(argv[1], "control") == 0;
    const double kp = control ? atof(argv[2]) : 0.0, kd = control ? atof(argv[3]) : 0.0;
    RotorRubParams params;
    RotorRubState initial;
    double start_time;
    int32_t rc = rotor_rub_preset(ROTOR_RUB_PRESET_PAPER, &params, &initial, &start_time);
    if (rc != ROTOR_RUB_OK) return fail("preset", rc);

    const double dt = 1e-3;
    RotorRubConfig config;
    rc = rotor_rub_config_default(&config);
    if (rc != ROTOR_RUB_OK) return fail("config", rc);
    config.dt = dt;
    if (control) config.on_cap = ROTOR_RUB_ON_CAP_FAIL;

    /* Caller-owned memory: no allocation anywhere. */
    static RotorRubStepper stepper;
    if (rotor_rub_stepper_size() > sizeof stepper) {
        fprintf(stderr, "RotorRubStepper is too small for this library\n");
        return 1;
    }
    rc = rotor_rub_stepper_init(&stepper, &params, &initial, start_time, &config);
    if (rc != ROTOR_RUB_OK) return fail("init", rc);

    const double period = 2.0 * acos(-1.0) / params.speed_ratio;
    const long steps = (long)ceil(PERIODS * period / dt - 1e-9);
    size_t count = 0;
    unsigned long dropped = 0, capped = 0, split = 0;
    RotorRubState measured = initial;
    for (long k = 1; k <= steps; ++k) {
        RotorRubStepResult r;
        if (control) {
            /* The controller: PD towards the stator centre, from the last measured state. */
            const double fx = -kp * (measured.x - params.offset_x) - kd * measured.vx;
            const double fy = -kp * (measured.y - params.offset_y) - kd * measured.vy;
            rc = rotor_rub_stepper_set_input_force(&stepper, fx, fy);
            if (rc != ROTOR_RUB_OK) return fail("input force", rc);
        }
        /* A step of dt; if it would exceed its bounded work, two half steps instead. */
        RotorRubStepResult parts[2];
        int n = 1;
        rc = rotor_rub_stepper_step(&stepper, dt, &parts[0]);
        if (rc == ROTOR_RUB_ERR_BUDGET_EXCEEDED) {
            ++split;
            n = 2;
            rc = rotor_rub_stepper_step(&stepper, 0.5 * dt, &parts[0]);
            if (rc == ROTOR_RUB_OK) rc = rotor_rub_stepper_step(&stepper, 0.5 * dt, &parts[1]);
        }
        if (rc != ROTOR_RUB_OK) return fail("step", rc);
        for (int p = 0; p < n; ++p) {
            const RotorRubStepResult *q = &parts[p];
            for (uint32_t i = 0; i < q->event_count && count < MAX_SWITCHES; ++i, ++count) {
                switch_time[count] = q->events[i].time;
                switch_kind[count] = q->events[i].kind;
                switch_state[count] = q->events[i].state;
            }
            dropped += q->dropped_events;
            capped += q->capped;
        }
        r = parts[n - 1];
        measured = r.state;
        if (k % CHECK_EVERY == 0) {
            printf("state %ld %.17g %.17g %.17g %.17g %.17g %d\n", k, r.time, r.state.x,
                   r.state.y, r.state.vx, r.state.vy, (int)r.regime);
        }
    }
    for (size_t i = 0; i < count; ++i) {
        const RotorRubState *s = &switch_state[i];
        printf("switch %zu %s %.17g %.17g %.17g %.17g %.17g\n", i,
               switch_kind[i] == ROTOR_RUB_EVENT_ENTER ? "enter" : "exit", switch_time[i], s->x,
               s->y, s->vx, s->vy);
    }
    printf("summary %ld %zu %lu %lu %lu\n", steps, count, dropped, capped, split);
    return 0;
}
