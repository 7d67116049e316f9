/* The stator ring with mass through the C ABI: the paper preset with a ring of mass
 * (stator_mass_ratio = 1, contact_stiffness = 100, stator_damping = 0.5, set by name through the
 * parameter table) for 10 forcing periods in fixed steps dt = 1e-2. Prints every switch with the
 * rotor's state, and the rotor's and the ring's state every 100 steps.
 *
 * Build as examples/paper.c (replace paper.c by ring.c).
 *
 * Output lines (numbers with 17 significant digits):
 *   state <step> <time> <x> <y> <vx> <vy> <xs> <ys> <vxs> <vys> <regime>
 *   switch <enter|exit|...:kind code> <time> <x> <y> <vx> <vy>
 *   summary <steps> <switches> <largest ring displacement>
 */
#include <math.h>
#include <stdio.h>

#include "rotor_rub.h"

static int fail(const char *what, int32_t code) {
    fprintf(stderr, "%s: %s (code %d)\n", what, rotor_rub_error_message(code), (int)code);
    return 1;
}

static int set(RotorRubParams *params, RotorRubState *initial, double *start_time,
               const char *name, double value) {
    int32_t index = -1;
    int32_t rc = rotor_rub_parameter_index(name, &index);
    if (rc != ROTOR_RUB_OK) return fail(name, rc);
    rc = rotor_rub_parameter_set(params, initial, start_time, index, value);
    if (rc != ROTOR_RUB_OK) return fail(name, rc);
    return 0;
}

int main(void) {
    RotorRubParams params;
    RotorRubState initial;
    double start_time;
    int32_t rc = rotor_rub_preset(ROTOR_RUB_PRESET_PAPER, &params, &initial, &start_time);
    if (rc != ROTOR_RUB_OK) return fail("preset", rc);
    if (set(&params, &initial, &start_time, "stator_mass_ratio", 1.0) ||
        set(&params, &initial, &start_time, "contact_stiffness", 100.0) ||
        set(&params, &initial, &start_time, "stator_damping", 0.5))
        return 1;

    const double dt = 1e-2;
    RotorRubConfig config;
    rc = rotor_rub_config_default(&config);
    if (rc != ROTOR_RUB_OK) return fail("config", rc);
    config.dt = dt;

    /* Caller-owned memory (ROTOR_RUB_STEPPER_WORDS 64-bit words): no allocation anywhere. */
    static RotorRubStepper stepper;
    if (rotor_rub_stepper_size() > sizeof stepper) {
        fprintf(stderr, "RotorRubStepper is too small for this library\n");
        return 1;
    }
    rc = rotor_rub_stepper_init(&stepper, &params, &initial, start_time, &config);
    if (rc != ROTOR_RUB_OK) return fail("init", rc);
    RotorRubRingState ring;
    int32_t is_ring = 0;
    rc = rotor_rub_stepper_ring_state(&stepper, &ring, &is_ring);
    if (rc != ROTOR_RUB_OK) return fail("ring state", rc);
    if (!is_ring) {
        fprintf(stderr, "a ring with mass must run the ring's stepper\n");
        return 1;
    }

    const double period = 2.0 * acos(-1.0) / params.speed_ratio;
    const long steps = (long)ceil(10.0 * period / dt - 1e-9);
    long switches = 0;
    double largest = 0.0;
    for (long k = 1; k <= steps; ++k) {
        RotorRubStepResult r;
        rc = rotor_rub_stepper_step(&stepper, dt, &r);
        if (rc != ROTOR_RUB_OK) return fail("step", rc);
        for (uint32_t i = 0; i < r.event_count; ++i, ++switches) {
            const RotorRubEvent *e = &r.events[i];
            printf("switch %d %.17g %.17g %.17g %.17g %.17g\n", (int)e->kind, e->time,
                   e->state.x, e->state.y, e->state.vx, e->state.vy);
        }
        rc = rotor_rub_stepper_ring_state(&stepper, &ring, NULL);
        if (rc != ROTOR_RUB_OK) return fail("ring state", rc);
        largest = fmax(largest, hypot(ring.xs, ring.ys));
        if (k % 100 == 0) {
            printf("state %ld %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %d\n", k,
                   r.time, r.state.x, r.state.y, r.state.vx, r.state.vy, ring.xs, ring.ys,
                   ring.vxs, ring.vys, (int)r.regime);
        }
    }
    printf("summary %ld %ld %.17g\n", steps, switches, largest);
    return 0;
}
