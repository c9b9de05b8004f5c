// The five lessons shipped with the page, in the lesson file format (js/lessons.js), one
// per theme of the method (../shared/METHOD.md): comfort against road holding, what the
// quarter car cannot see, the design objective space, why a surrogate, and choosing one
// design. Every number in a reveal is a placeholder the page fills in for the car and
// road shown; the prose says what to look at, the numbers say what happened. A step with
// options states its right one (`answer`, 1..), marked at the reveal: each was decided
// from the numbers the page computes at the step's view (the comments quote them, for the
// shipped sedan), and tests/e2e/lessonanswers.test.mjs checks each against them by a rule.

/** `[{id, lesson}]`: `id` names it in a link (`#lesson=comfort`). */
export const SHIPPED = [
  {
    id: 'comfort',
    lesson: {
      ridelab: 'lesson',
      version: 1,
      title: 'Comfort against road holding',
      steps: [
        {
          view: 'ks=19960&cs=1290',
          question: 'The datum car on a class {class} road at {speed}. Which number is comfort and which is road holding?',
          options: ['BAcc is comfort, DTL is road holding', 'DTL is comfort, BAcc is road holding', 'SWS is both'],
          // A definition (the method's, as the reveal says): body acceleration is comfort, tyre-load swing road holding.
          answer: 1,
          reveal: 'BAcc, the RMS body acceleration above the front wheel, is comfort: {hifi.bacc} on the full car, {lofi.bacc} on the quarter car. DTL, the RMS swing of the tyre\'s grip force, is road holding: {hifi.dtl}, {hifi.dtlrel} of the static wheel load. The working space SWS, {hifi.sws}, must stay within the {sws_limit} limit.',
          highlight: ['map-grid', 'criteria'],
        },
        {
          view: 'ks=14000&cs=1290',
          question: 'The spring goes from {datum.ks} down to {ks}; the damper stays. What happens to BAcc and DTL?',
          options: ['Both fall', 'BAcc falls, DTL rises', 'BAcc rises, DTL falls', 'Both rise'],
          // Sedan, class B, 20 m/s: BAcc -11.0 % (LoFi), -10.3 % (HiFi); DTL -1.0 %, -0.8 %.
          answer: 1,
          reveal: 'Against the datum the quarter car says BAcc {lofi.bacc.pct}, DTL {lofi.dtl.pct}; the full car BAcc {hifi.bacc.pct}, DTL {hifi.dtl.pct}. The body now bounces at {bounce}. SWS is {hifi.sws} ({hifi.sws.pct}): for the quarter car var(SWS) = W (ms + mu) / (2 cs) does not depend on the spring at all. Why not softer still? Below {ks_dtl} DTL rises again, and a soft spring sags under load (not in these models).',
          highlight: ['ks-range', 'map-grid'],
          hide: ['criteria'],
        },
        {
          view: 'ks=19960&cs=2500',
          question: 'Back to the datum spring; the damper goes from {datum.cs} up to {cs}. What happens to BAcc and DTL?',
          options: ['Both fall', 'BAcc falls, DTL rises', 'BAcc rises, DTL falls', 'Both rise'],
          // BAcc +16.5 % (LoFi), +17.0 % (HiFi); DTL -8.3 % on both.
          answer: 3,
          reveal: 'Against the datum: BAcc {lofi.bacc.pct} (LoFi), {hifi.bacc.pct} (HiFi); DTL {lofi.dtl.pct} (LoFi), {hifi.dtl.pct} (HiFi); SWS {hifi.sws.pct}. Damping holds the wheel on the road, but it also pushes road bumps into the body.',
          highlight: ['cs-range', 'map-grid'],
          hide: ['criteria'],
        },
        {
          view: 'ks=19960&cs=1290',
          question: 'Keep Ks at {ks} and drag Cs: where along the damper axis is BAcc lowest, and is DTL lowest there too?',
          options: ['Below the datum damper, and DTL agrees', 'Below the datum damper, DTL wants more', 'Above the datum damper, DTL wants less'],
          // {cs_opt} 1.074 kNs/m is below {datum.cs} 1.29; {cs_dtl} 2.375 is above both.
          answer: 2,
          reveal: 'For the quarter car var(BAcc) = W (ks² (ms + mu) + cs² kt) / (2 cs ms²) is lowest at cs = ks √((ms + mu) / kt) = {cs_opt} (ks {ks}, ms {ms}, mu {mu}, kt {kt}); the datum has {datum.cs}. var(DTL) carries the wheel hop, kt² mu / cs, which wants damping: its optimum is {cs_dtl}. Between the two no damper is best for both; that is the trade-off the front on the objective plane traces.',
          highlight: ['cs-range', 'map-bacc', 'map-dtl', 'op-wrap'],
        },
      ],
    },
  },
  {
    id: 'fidelity',
    lesson: {
      ridelab: 'lesson',
      version: 1,
      title: 'What the quarter car cannot see',
      steps: [
        {
          view: 'ks=19960&cs=1290&speed=20',
          question: 'The quarter car (LoFi) is one corner. The full car (HiFi) adds pitch, roll and the rear wheels, which meet each bump {delay} after the front. Which criterion differs most between them?',
          options: ['BAcc', 'DTL', 'SWS'],
          // At 20 m/s the gaps are BAcc +1.9 %, DTL -0.2 %, SWS -1.3 %.
          answer: 1,
          reveal: 'HiFi against LoFi at {speed}: BAcc {gap.bacc}, DTL {gap.dtl}, SWS {gap.sws}. BAcc is read on the body above the front wheel, which also pitches when the rear wheels, {wheelbase} behind, take the same bump.',
          highlight: ['criteria'],
        },
        {
          view: 'ks=19960&cs=1290&speed=10',
          question: 'Slow down to {speed}: the rear wheels now lag by {delay}. Does the BAcc gap between the models grow or shrink?',
          options: ['It grows', 'It shrinks', 'It stays the same'],
          // The BAcc gap: +1.3 % at 10 m/s against +1.9 % at 20 m/s.
          answer: 2,
          reveal: 'At {speed} the BAcc gap is {gap.bacc} (DTL {gap.dtl}). Front and rear inputs cancel in heave where the lag is half a period, first at 1 / (2 L / v) = {heave_null}, and add up in pitch there: the wheelbase filters the road differently at every speed, and the quarter car sees none of it.',
          highlight: ['speed', 'criteria'],
          hide: ['criteria'],
        },
        {
          view: 'ks=19960&cs=1290&speed=40',
          question: 'Now {speed}. Grow or shrink?',
          options: ['It grows', 'It shrinks', 'It stays the same'],
          // The BAcc gap: +2.5 % at 40 m/s against +1.9 % at 20 and +1.3 % at 10 m/s.
          answer: 1,
          reveal: 'At {speed}: BAcc gap {gap.bacc}, DTL gap {gap.dtl}; the first heave cancellation moved up to {heave_null}, closer to the wheel hop. Type other speeds into the Speed field and watch the HiFi column move against the LoFi one.',
          highlight: ['speed', 'criteria'],
          hide: ['criteria'],
        },
        {
          view: 'ks=19960&cs=1290&model=hifi',
          question: 'The maps now show the full car. Do the quarter car\'s conclusions about softer springs and more damping still hold?',
          options: ['Yes, the shapes are alike', 'No, the shapes differ'],
          // The HiFi maps' BAcc and DTL planes correlate with the LoFi ones over the box (Pearson r > 0.98).
          answer: 1,
          reveal: 'The HiFi maps have the LoFi\'s shape: at this design HiFi BAcc is {hifi.bacc} against LoFi {lofi.bacc}, DTL {hifi.dtl} against {lofi.dtl}. Where the shapes agree the quarter car ranks designs well; the gaps in its numbers are what a surrogate corrects.',
          highlight: ['map-grid', 'map-model'],
        },
      ],
    },
  },
  {
    id: 'objectives',
    lesson: {
      ridelab: 'lesson',
      version: 1,
      title: 'The design objective space',
      steps: [
        {
          view: 'ks=19960&cs=1290&sws=7',
          question: 'The SWS limit is {sws_limit} RMS. Which designs break it: soft or stiff springs, light or heavy damping?',
          options: ['Light damping, whatever the spring', 'Soft springs, whatever the damping', 'Stiff springs with heavy damping'],
          // The cells over 7 mm are whole Cs rows, from the lowest Cs up to about {cs_sws} 1.309 kNs/m, at every Ks.
          answer: 1,
          reveal: 'For the quarter car var(SWS) = W (ms + mu) / (2 cs): the working space depends on the damper alone, so the limit is a horizontal edge on the maps at cs = {cs_sws}. {feasible} of the box meets the objectives on this road.',
          highlight: ['map-sws', 'sws-range'],
        },
        {
          view: 'ks=19960&cs=1290&sws=7&bb=0.8,1.5',
          question: 'Comfort guides ask for a body bounce between 0.8 and 1.5 Hz. Which springs does that band rule out in this box?',
          options: ['The softest springs', 'The stiffest springs', 'None'],
          // Only the softest Ks columns break the 0.8..1.5 Hz band; no column at the stiff end does.
          answer: 1,
          reveal: 'With the band on, {feasible} of the box is left (the dotted hatching breaks the band). This design bounces at {bounce}. The body bounce grows with the square root of the spring, so the band cuts the soft end of the box.',
          highlight: ['map-grid', 'bb-lo'],
        },
        {
          view: 'ks=19960&cs=1290&sws=7&class=C',
          question: 'The same car on a class {class} road (average, four times the roughness of B). How much of the box meets SWS ≤ {sws_limit}?',
          options: ['Most of it', 'About half', 'None of it'],
          // Class C: {feasible} 0 %; the smallest SWS in the box is 7.8 mm.
          answer: 3,
          reveal: '{feasible} of the box meets the objectives on class {class}: {front.status}. The quarter car needs cs ≥ {cs_sws} to keep SWS within {sws_limit}, and the box ends at {box.cs_max}. Here SWS is {lofi.sws} (LoFi). The page says so rather than drawing an empty front: loosen the limit, slow down or enlarge the box.',
          highlight: ['map-grid', 'op-msg', 'class'],
          hide: ['map-grid', 'map-status', 'op-msg'],
        },
      ],
    },
  },
  {
    id: 'surrogate',
    lesson: {
      ridelab: 'lesson',
      version: 1,
      title: 'Why a surrogate',
      steps: [
        {
          view: 'ks=19960&cs=1290&model=hifi',
          question: 'Each of these HiFi maps took {grid.cells} full-car runs. How many HiFi runs does the surrogate use?',
          options: ['About ten', 'About a thousand', 'All of them'],
          // {samples} 10 (plan ae:10) against {grid.cells} 19200.
          answer: 1,
          reveal: 'The surrogate (the quarter car tuned to the full car, plan {plan}) is fitted to {samples} HiFi runs, the × marks. The front on the objective plane then took {front.evals} surrogate evaluations.',
          highlight: ['map-grid', 'show-plan'],
        },
        {
          view: 'ks=19960&cs=1290&model=error',
          question: 'The maps show the surrogate\'s error against the full car. How large is its worst error?',
          options: ['Under 1 %', 'A few per cent', 'Over 10 %'],
          // The worst is BAcc: 0.67 % on the 20 × 20 HiFi grid ({fit.rte.bacc}), 0.64 % on the error maps.
          answer: 1,
          reveal: 'On a 20 × 20 HiFi grid its largest error is {fit.rte.bacc} in BAcc, {fit.rte.dtl} in DTL and {fit.rte.sws} in SWS (mean {fit.rte_mean.bacc}, {fit.rte_mean.dtl}, {fit.rte_mean.sws}). At the min-max pick its prediction differs from the HiFi re-check by {recheck.err}.',
          highlight: ['map-grid'],
        },
        {
          view: 'ks=19960&cs=1290&plan=ae:3&model=error',
          question: 'Only {plan} now: three HiFi runs. Where will the pick go, and will the HiFi still agree?',
          options: ['Same pick, same agreement', 'The pick moves, the HiFi disagrees more'],
          // With ae:3 the pick moves a little (Cs 1681 to 1667 N s/m, Ks the same) and {recheck.err} grows
          // from 0.11 % to 0.54 %: both true, if small (still under 1 %), as the reveal's last sentence says.
          answer: 2,
          reveal: 'With {samples} HiFi runs the largest errors are {fit.rte.bacc} (BAcc) and {fit.rte.dtl} (DTL). The pick is Ks {pick.ks}, Cs {pick.cs}; its HiFi re-check differs by {recheck.err}. The LoFi physics carries the surrogate between the samples, which is why so few runs go so far.',
          highlight: ['op-wrap', 'map-grid'],
        },
      ],
    },
  },
  {
    id: 'choosing',
    lesson: {
      ridelab: 'lesson',
      version: 1,
      title: 'Choosing one design',
      steps: [
        {
          view: 'ks=19960&cs=1290',
          question: 'The orange line on the objective plane is the Pareto front. What does a design on it promise?',
          options: ['Nothing beats it in both BAcc and DTL', 'It is the most comfortable design', 'It meets every objective with margin'],
          // No front point is dominated; only one end is the most comfortable; the comfort end sits on the SWS limit (no margin).
          answer: 1,
          reveal: 'There are {front.status}, each feasible; from one to the next, comfort is bought with road holding. The datum (square) is at BAcc {sur.datum.bacc}, DTL {sur.datum.dtl} on the surrogate: off the front, so some designs beat it in both.',
          highlight: ['op-wrap'],
        },
        {
          view: 'ks=19960&cs=1290&axes=ratio',
          question: 'On ratio axes the datum sits at (1, 1). The min-max pick keeps the larger of its two distances from the ideal point smallest. Where will it lie?',
          options: ['At the comfort end of the front', 'In the middle of the front', 'At the road-holding end'],
          // The pick is neither end: its BAcc and its DTL each lie 34 % of the front's span from their best (pseudo-weights 0.50 / 0.50).
          answer: 2,
          reveal: 'The pick (diamond): Ks {pick.ks}, Cs {pick.cs}; the surrogate predicts BAcc {pick.bacc.pct}, DTL {pick.dtl.pct} and SWS {pick.sws.pct} against the datum.',
          highlight: ['op-wrap', 'to-pick'],
        },
        {
          view: 'ks=19960&cs=1290&axes=ratio',
          question: 'The pick came from the surrogate. Press Pick (K) to go there. Will the full car confirm it?',
          options: ['Yes, within about 1 %', 'Roughly, within 10 %', 'No'],
          // {recheck.err} 0.11 %.
          answer: 1,
          reveal: 'Re-checked on the HiFi: BAcc {recheck.bacc} ({recheck.bacc.pct} against the HiFi datum), DTL {recheck.dtl} ({recheck.dtl.pct}), SWS {recheck.sws}; the surrogate was off by {recheck.err} at most. One HiFi run checks the choice the surrogate made.',
          highlight: ['to-pick', 'op-wrap'],
        },
        {
          view: 'ks=19960&cs=1290&axes=ratio&sws=6',
          question: 'Tighten the SWS limit to {sws_limit}. Where does the pick go?',
          options: ['Towards more damping', 'Towards less damping', 'Nowhere'],
          // {pick.cs} goes from 1.681 to 2.002 kNs/m ({cs_sws} 1.782 kNs/m at 6 mm).
          answer: 1,
          reveal: 'Now the pick is Ks {pick.ks}, Cs {pick.cs}: BAcc {pick.bacc.pct}, DTL {pick.dtl.pct} against the datum (HiFi re-check {recheck.bacc.pct}, {recheck.dtl.pct}). A tighter limit needs cs ≥ {cs_sws} on the quarter car, so the front loses its lightly damped, most comfortable end.',
          highlight: ['op-wrap', 'sws-range'],
        },
      ],
    },
  },
];
