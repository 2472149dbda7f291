"""Analysis of motion records and the project report.

* :mod:`~floatfoam.analysis.decay`: period and damping of a free-decay record (crossings,
  log decrements, :mod:`~floatfoam.analysis.decay_fit` damped-sinusoid fits with 95 % CIs);
  :mod:`~floatfoam.analysis.released` the DoFs a record is analysed in, and its noise floor;
* :mod:`~floatfoam.analysis.compare`: one table per case: memoir, theory, potential flow,
  Cummins' model (:mod:`~floatfoam.analysis.cummins`, the Δ columns' basis), CFD runs (found
  by :mod:`~floatfoam.analysis.runs`; their first cycles about the level of
  :mod:`~floatfoam.analysis.settled`) and the published reference
  (:mod:`~floatfoam.analysis.measured`), written by :mod:`~floatfoam.analysis.comparison_table`;
* :mod:`~floatfoam.analysis.plots`: decay figures (:mod:`~floatfoam.analysis.overlay`: what
  they set beside a record);
* :mod:`~floatfoam.analysis.report`: every case in one Markdown + HTML report
  (:mod:`~floatfoam.analysis.document` renders both from one list of blocks).
"""
