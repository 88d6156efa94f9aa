"""Grading a class: the assignment, the submissions, the batch run and the report folder.

- :mod:`~dhsym.checking.grading.batch`: :func:`~dhsym.checking.grading.batch.grade`
  (``dhsym grade``);
- :mod:`~dhsym.checking.grading.submissions`: a folder or CSV of submissions, read defensively;
- :mod:`~dhsym.checking.grading.records`: the record of one graded submission;
- :mod:`~dhsym.checking.grading.feedback`: feedback pages (Markdown, HTML, text);
- :mod:`~dhsym.checking.grading.report`: the gradebook and the summary page;
- :mod:`~dhsym.checking.grading.sandbox`: a killable child process per worker (its framing,
  its deadline); :mod:`~dhsym.checking.grading.backends`: the serial run, the pool of
  sandboxes, a Dask cluster, the progress bar.
"""
