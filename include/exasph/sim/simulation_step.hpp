#pragma once
// The definitions of Simulation's step machinery (sim/simulation.hpp declares them, with what
// each does); included at the end of simulation.hpp, not on its own.

namespace exasph {

template <class T, class L>
void Simulation<T, L>::begin_step() {
    timer_.begin_step();
    recovered_ = false;
    flags_.begin_step();
    const Box<T> fitted = box_fresh_ ? box_ : with_open_axes_unbounded(box_); // to check
    const StepStart start = safety_.begin_step(ps_, n_owned(), fitted, clock_.step + 1,
                                               clock_.dt_m1, eos_.kind == EosKind::ideal_gas);
    if (start.corrupt) flags_.raise(kCorruptBefore);
    point_pending_ |= start.point_due;     // block steps: waits for a block's end
    if (point_pending_) sched_.ask_sync(); // a rollback point follows a sync's vote
    advanced_ = false;
}

template <class T, class L>
void Simulation<T, L>::end_phase(Phase p) {
    timer_.stop(p);
    if (safety_.phase_ended(p, ps_, n_owned())) flags_.raise(kStateChanged);
}

template <class T, class L>
bool Simulation<T, L>::sync_or_refresh() {
    if (!sched_.sync_due()) {
        domain_.refresh(ps_);
        return end_phase(kSync), true;
    }
    if (!box_fresh_) refit_box_to_particles(ps_, n_owned(), box_, domain_.collectives());
    const bool by_cost = cfg_.balance == Balance::cost && blocks_;
    domain_.count_particles(ps_, box_, &flags_, by_cost ? blocks_->costs(ps_, n_owned()) : nullptr);
    if (flags_[kCorruptBefore]) return false;
    if (point_pending_ && at_sync_point())
        safety_.keep_point(ps_, n_owned(), run_point()), point_pending_ = false;
    domain_.distribute(ps_, box_);
    if (blocks_) blocks_->select(ps_, n_owned(), work_);
    sched_.synced(n_owned());
    end_phase(kSync);
    return true;
}

template <class T, class L>
void Simulation<T, L>::compute_forces() {
    const KernelView<T> k = kernel_.view(); // HydroInputs holds a reference to it
    const HydroInputs<T> in{box_, k, eos_, cfg_, gravity_ ? &*gravity_ : nullptr, clock_.step == 0};
    courant_dt_ = hydro_forces<L>(ps_, nlists_, in, domain_, phase_ender(),
                                  store_results_in(blocks_ ? ps_.data(Field::dtc) : nullptr));
    if (!blocks_) nlists_.release(); // the sync can use their memory
    end_phase(kMomentumEnergy);
    if (gravity_)
        gravity_->compute(ps_, n_owned(), domain_.assignment(), box_, domain_.curve(),
                          domain_.collectives(), blocks_ ? blocks_->active() : nullptr);
    if (stirring_) add_stirring<L>(ps_, n_owned(), stirring_->modes());
    end_phase(kGravity);
}

template <class T, class L>
void Simulation<T, L>::advance_and_diagnose(double dt) {
    advance(dt);
    before_ = diag_;
    const bool forced = // the run's end, or a stop or a clock checkpoint after the step
        clock_.ends(cfg_.steps) || flags_[kStopRequested] || flags_[kCheckpointByClock];
    summed_ = sched_.diagnose_due(clock_.step, safety_on_, forced);
    diagnose(dt, summed_);
    advanced_ = true;
}

template <class T, class L>
void Simulation<T, L>::conclude() {
    // The watchdog compares two sums only when they are of consecutive steps.
    const bool consecutive = advanced_ && summed_ && before_.step + 1 == diag_.step;
    const StepOutcome outcome{.step = clock_.step,
                              .corrupt_before = flags_[kCorruptBefore],
                              .state_changed = flags_[kStateChanged],
                              .before = consecutive ? &before_ : nullptr,
                              .now = advanced_ ? &diag_ : nullptr,
                              .mass0 = mass0_,
                              .check_momentum = !gravity_ && !stirring_};
    if (const RunPoint<T>* point = safety_.conclude(ps_, n_owned(), outcome)) {
        box_ = point->box, box_fresh_ = true;
        diag_ = point->diag;
        sched_.ask_sync(); // the halos and trees belong to the state left behind
        resume(point->rs);
        recovered_ = true;
    } else {
        end_phase(kDiagnostics);
    }
    timer_.end_step();
}

template <class T, class L>
void Simulation<T, L>::find_neighbours() {
    const auto res =
        build_neighbour_lists(nlists_, domain_, ps_, box_, blocks_ ? blocks_->active() : nullptr);
    max_list_ = res.max_count;
    work_.active = double(blocks_ ? blocks_->active_count() : n_owned()),
    work_.pairs = double(res.pairs);
}

template <class T, class L>
double Simulation<T, L>::choose_time_step() {
    const double accel = gravity_ ? cfg_.accel_eps : 0.0;
    if (blocks_) { // closing and opening steps updates the state (the net checked it first)
        const double dt =
            blocks_->choose(ps_, n_owned(), nlists_, domain_,
                            {clock_.step == 0, clock_.dt0, accel, clock_.time, clock_.t_end});
        nlists_.release();
        return dt;
    }
    const double limit = local_time_step_limit<L>(ps_, n_owned(), courant_dt_, accel);
    if (!sched_.votes()) return clock_.step_from(domain_.collectives().allreduce_min(limit));
    return sched_.voted_step<L>(ps_, n_owned(), limit, clock_, cfg_.ng0, domain_, flags_);
}

template <class T, class L>
void Simulation<T, L>::advance(double dt) {
    const double t_next = advance_state<L>(ps_, n_owned(), box_, blocks_ ? &*blocks_ : nullptr,
                                           cfg_, dt, clock_, phase_ender());
    if (stirring_) stirring_->advance(clock_.step, dt);
    clock_.stepped(dt, t_next);
    box_fresh_ = false, sched_.stepped();
}

template <class T, class L>
void Simulation<T, L>::diagnose(double dt, bool summed) {
    const double waited = domain_.comm_record().waited_in_step(); // compute: the rest
    work_.compute_sum = work_.compute_max = std::max(0.0, timer_.step_total() - waited);
    if (summed)
        diag_ = sum_diagnostics<L>(
            ps_, n_owned(), domain_.n_halo(), exact_.at(clock_.time - dt, exact_table_.data()),
            clock_.step > 0, cfg_.ng0, work_, flags_, box_, domain_.collectives());
    diag_.step = clock_.step, diag_.time = clock_.time, diag_.dt = dt;
    if (!summed) return;
    if (stirring_) stirring_->add_energy(dt * diag_.stir_power);
    diag_.e_stir = stirring_ ? stirring_->state().energy_in : 0.0;
    box_fresh_ = true;
}

} // namespace exasph
