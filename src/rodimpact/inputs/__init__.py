"""The files a user hands the workflow, read safely: the configuration, the case files and every
file a case points to (force histories, and every record kind after them).

What lives here: :mod:`.files`: :func:`~rodimpact.inputs.files.regular_file` (a path's link
resolved, and only a regular file accepted: never a read of a FIFO, a device or a directory),
:func:`~rodimpact.inputs.files.read_text` (bounded in size, decoded with a declared encoding,
a bad byte named by its line and column), :func:`~rodimpact.inputs.files.quoted` (a value in a
message, at most about 100 characters of it) and :class:`~rodimpact.inputs.files.InputFileError`
(the error, with the file and the reason as data).

What it may import: the standard library only. It is the lowest layer beside
:mod:`rodimpact.settings`: the configuration and the measurements are read with it.
"""
