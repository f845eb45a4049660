"""Where the build book's files go in an export (read by the book's writer,
:mod:`tactcad.export.instructions`, and by the review page, which shows its steps)."""

BOOK_DIR = "instructions"
BOOK_PAGE = f"{BOOK_DIR}/index.html"
BOOK_DATA = f"{BOOK_DIR}/steps.json"
BOOK_PDF = f"{BOOK_DIR}/build_book.pdf"
