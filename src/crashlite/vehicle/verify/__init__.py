"""Verification of a simplified vehicle against its full model (the
paper's section 4): the comparison (``verification``), the verdict on its
figures (``verdict``) and the pages of a verification, a reduction and the
paper study (``verification_report``, ``reduce_report``,
``study_report``)."""
