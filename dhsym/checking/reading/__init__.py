"""Reading answers: untrusted student text (plain math, LaTeX, Markdown/YAML tables) to sympy.

- :mod:`~dhsym.checking.reading.answer_value`: an answer read once into the typed value
  judging takes (:class:`~dhsym.checking.reading.answer_value.MatrixAnswer`, ``TableAnswer``,
  ``IKAnswer``);
- :mod:`~dhsym.checking.reading.answers`: an expression, a matrix or a DH table from text;
- :mod:`~dhsym.checking.reading.latex_input`: LaTeX (``\\begin{bmatrix}``, ``\\cos``) to plain math;
- :mod:`~dhsym.checking.reading.answer_names`: the names a student may use for a key's symbols;
- :mod:`~dhsym.checking.reading.questions`: what is asked (``T0_2``, ``J[0,1]``, ``ik``, ``M``);
- :mod:`~dhsym.checking.reading.limits`: the sizes, time and cost bounds on everything read.

Nothing here judges: the judging room (:mod:`dhsym.checking.judging`) compares what was read
with the key.
"""
