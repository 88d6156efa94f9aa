"""Identifiers and comments for generated code that no robot name can break.

A robot's name, its variable names and a prefix come from a user: in generated code
they become identifiers only through :func:`identifier` (ASCII letters, digits and
``_``, starting with a letter, never a keyword of any target language) and text only
through :func:`comment_lines` (printable ASCII, no sequence that ends or opens a
comment in C, C++, Rust, MATLAB/Octave or Python).

A prefix names functions and files, so :func:`prefix` takes it only when it is a name
(:func:`checked_name` refuses a path, a leading digit, other characters), and suffixes a
``_`` to one that is a keyword (:data:`KEYWORDS`) or a standard name of the target language
(:data:`RESERVED`, :func:`reserved`: ``log`` in C++, ``os`` in Python): suffixed, never
refused, as keywords always were. The lists of each language are kept here, and only here.

Examples
--------
>>> identifier("PUMA 560")
'puma_560'
>>> identifier("*/ int main(){")
'int_main'
>>> identifier("for")
'for_'
>>> comment_lines("θ1 */ evil\\n%{ more ??/")
['theta1 * / evil', '% { more ? ?/']
"""

from __future__ import annotations

import re
import unicodedata
from collections.abc import Mapping
from types import MappingProxyType

from dhsym.errors import DHError

__all__ = [
    "KEYWORDS",
    "RESERVED",
    "checked_name",
    "comment_lines",
    "identifier",
    "prefix",
    "reserved",
]

# Keywords and reserved words, by language (what no generated identifier may be).
_C_KEYWORDS = """
    auto break case char const continue default do double else enum extern float for goto if
    inline int long register restrict return short signed sizeof static struct switch typedef
    union unsigned void volatile while
"""
_CPP_KEYWORDS = """
    alignas alignof and and_eq asm bitand bitor bool catch class compl constexpr const_cast
    decltype delete dynamic_cast explicit export false friend mutable namespace new noexcept not
    not_eq nullptr operator or or_eq private protected public reinterpret_cast static_assert
    static_cast template this thread_local throw true try typeid typename using virtual wchar_t
    xor xor_eq
"""
_RUST_KEYWORDS = """
    as crate dyn fn impl in let loop match mod move mut pub ref self Self super trait type unsafe
    use where async await abstract become box final macro override priv typeof unsized yield
"""
_MATLAB_KEYWORDS = """
    end endfor endif endwhile endfunction function global persistent elseif otherwise parfor spmd
    unwind_protect
"""
_PYTHON_KEYWORDS = """
    None True False assert def del elif except finally from import is lambda nonlocal pass raise
    with print
"""
# The names the templates themselves use (a local or a parameter may not take them).
_TEMPLATE_NAMES = """
    main std math numpy np q T J p sol count b k i j f64 usize isize i32 u32 pi e inf nan sqrt sin
    cos atan2 remainder fabs abs max min
"""

#: Words no generated identifier may equal: keywords and reserved words of C99, C++17,
#: Rust, MATLAB/Octave and Python, and the names the templates themselves use.
KEYWORDS = frozenset(
    (
        _C_KEYWORDS
        + _CPP_KEYWORDS
        + _RUST_KEYWORDS
        + _MATLAB_KEYWORDS
        + _PYTHON_KEYWORDS
        + _TEMPLATE_NAMES
    ).split()
)

# What a prefix may not be, by language, besides a keyword: the standard names it would meet.
# C: <prefix>.h would hide a standard header of that name (#include "math.h").
_C_HEADERS = """
    assert complex ctype errno fenv float inttypes iso646 limits locale math setjmp signal
    stdalign stdarg stdatomic stdbool stddef stdint stdio stdlib stdnoreturn string tgmath threads
    time uchar wchar wctype
"""
# C++: namespace <prefix> at global scope meets every name the C library declares there
# (<cmath> brings <stdlib.h> along in libstdc++; g++ defines _GNU_SOURCE, so glibc's POSIX
# and GNU names too), each also with the suffixes of _FLOAT_VARIANTS.
_CPP_GLOBAL_NAMES = """
    a64l abort abs acos acosh aligned_alloc arc4random arc4random_buf arc4random_uniform
    asctime asin asinh asprintf assert at_quick_exit atan atan2 atanh atexit atof atoi atol
    atoll basename bcmp bcopy bsearch bzero calloc canonicalize canonicalize_file_name cbrt
    ceil clearenv clearerr clock clock_adjtime clock_getcpuclockid clock_getres
    clock_gettime clock_nanosleep clock_settime clock_t copysign cos cosh ctermid ctime
    cuserid daddl daylight ddivl dfmal difftime div div_t dmull double_t dprintf drand48
    drem dsqrtl dsubl dysize ecvt erand48 erf erfc errno exit exp exp10 exp2 explicit_bzero
    expm1 f32addf128 f32addf32x f32addf64 f32addf64x f32divf128 f32divf32x f32divf64
    f32divf64x f32fmaf128 f32fmaf32x f32fmaf64 f32fmaf64x f32mulf128 f32mulf32x f32mulf64
    f32mulf64x f32sqrtf128 f32sqrtf32x f32sqrtf64 f32sqrtf64x f32subf128 f32subf32x
    f32subf64 f32subf64x f32xaddf128 f32xaddf64 f32xaddf64x f32xdivf128 f32xdivf64
    f32xdivf64x f32xfmaf128 f32xfmaf64 f32xfmaf64x f32xmulf128 f32xmulf64 f32xmulf64x
    f32xsqrtf128 f32xsqrtf64 f32xsqrtf64x f32xsubf128 f32xsubf64 f32xsubf64x f64addf128
    f64addf64x f64divf128 f64divf64x f64fmaf128 f64fmaf64x f64mulf128 f64mulf64x f64sqrtf128
    f64sqrtf64x f64subf128 f64subf64x f64xaddf128 f64xdivf128 f64xfmaf128 f64xmulf128
    f64xsqrtf128 f64xsubf128 fabs fadd fclose fcloseall fcvt fdim fdiv fdopen feclearexcept
    fegetenv fegetexceptflag fegetround feholdexcept fenv_t feof feraiseexcept ferror
    fesetenv fesetexceptflag fesetround fetestexcept feupdateenv fexcept_t fflush ffma ffs
    ffsll fgetc fgetpos fgets file fileno finite float_t flockfile floor fma fmax fmaximum
    fmaximum_mag fmaximum_mag_num fmaximum_num fmaxmag fmemopen fmin fminimum fminimum_mag
    fminimum_mag_num fminimum_num fminmag fmod fmul fopen fopencookie fpclassify fpos_t
    fprintf fputc fputs fread free freopen frexp fromfp fromfpx fscanf fseek fseeko fsetpos
    fsqrt fsub ftell ftello ftrylockfile funlockfile fwrite gamma gcvt getc getchar getdate
    getdate_err getdelim getenv getline getloadavg getpayload getpt getsubopt getw gmtime
    grantpt hypot ilogb imaxabs imaxdiv imaxdiv_t index initstate int16_t int32_t int64_t
    int8_t int_fast8_t int_least8_t intmax_t intptr_t isalnum isalpha isblank iscntrl
    isdigit isfinite isgraph isgreater isgreaterequal isinf isinff isinfl isless islessequal
    islessgreater islower isnan isnanf isnanl isnormal isprint ispunct isspace isunordered
    isupper isxdigit j0 j1 jmp_buf jn jrand48 l64a labs lcong48 lconv ldexp ldiv ldiv_t
    lgamma llabs lldiv lldiv_t llogb llrint llround localeconv localtime log log10 log1p
    log2 logb longjmp lrand48 lrint lround malloc math_errhandling max_align_t mblen
    mbstate_t mbstowcs mbtowc memccpy memchr memcmp memcpy memfrob memmem memmove mempcpy
    memrchr memset mkdtemp mkostemp mkostemps mkstemp mkstemps mktemp mktime modf mrand48
    nan nanosleep nearbyint nextafter nextdown nexttoward nextup nrand48 obstack_printf
    obstack_vprintf offsetof on_exit open_memstream pclose perror popen posix_memalign
    posix_openpt pow printf program_invocation_name program_invocation_short_name pselect
    ptrdiff_t ptsname putc putchar putenv puts putw qecvt qfcvt qgcvt qsort quick_exit raise
    rand random rawmemchr realloc reallocarray realpath remainder remove remquo rename
    renameat renameat2 rewind rindex rint round roundeven rpmatch scalb scalbln scalbn scanf
    secure_getenv seed48 select setbuf setbuffer setenv setjmp setlinebuf setlocale
    setpayload setpayloadsig setstate setvbuf sig_atomic_t sigabbrev_np sigdescr_np signal
    signbit signgam significand sin sincos sinh size_t snprintf sprintf sqrt srand srand48
    srandom sscanf stderr stdin stdout stpcpy stpncpy strcasecmp strcasestr strcat strchr
    strchrnul strcmp strcoll strcpy strcspn strdup strerror strerrordesc_np strerrorname_np
    strfromd strfromf strfromf128 strfromf32 strfromf32x strfromf64x strfroml strfry
    strftime strlen strncasecmp strncat strncmp strncpy strndup strnlen strpbrk strptime
    strrchr strsep strsignal strspn strstr strtod strtof strtof128 strtof32 strtof32x
    strtof64_l strtof64x strtoimax strtok strtol strtold strtoll strtoq strtoul strtoull
    strtoumax strtouq strverscmp strxfrm system tan tanh tempnam tgamma time time_t timegm
    timelocal timer_create timer_delete timer_getoverrun timer_gettime timer_settime
    timespec timespec_get timespec_getres timezone tm tmpfile tmpnam tolower totalorder
    totalordermag toupper trunc tzname tzset ufromfp ufromfpx uint16_t uint32_t uint64_t
    uint8_t uintmax_t uintptr_t ungetc unlockpt unsetenv va_arg va_copy va_end va_list
    va_start valloc vasprintf vdprintf vfprintf vfscanf vprintf vscanf vsnprintf vsprintf
    vsscanf wcstombs wctomb wint_t y0 y1 yn
"""
#: The float, long double and _FloatN variants of a C library name (``logf``, ``logl``,
#: ``logf128``), the reentrant, locale and 64-bit ones (``rand_r``, ``strtol_l``, ``fopen64``)
_FLOAT_VARIANTS = ("f", "l", "f16", "f32", "f64", "f128", "f32x", "f64x", "f128x")
_OTHER_VARIANTS = ("_r", "_l", "64", "_unlocked")
# Rust: mod <prefix> at the crate root hides a primitive type or a crate of that name.
_RUST_NAMES = """
    bool char str i8 i16 i32 i64 i128 isize u8 u16 u32 u64 u128 usize f32 f64 core alloc
    proc_macro
"""
# MATLAB/Octave: the prefix only occurs as <prefix>_fk, <prefix>_ik ...: keywords only.
_MATLAB_NAMES = ""
# Python: <prefix>.py beside a script hides the standard module of that name (os, sys,
# typing; Python 3.10 to 3.14), and numpy, which the module imports.
_PYTHON_MODULES = """
    abc aifc annotationlib antigravity argparse array ast asynchat asyncio asyncore atexit
    audioop base64 bdb binascii bisect builtins bz2 calendar cgi cgitb chunk cmath cmd code
    codecs codeop collections colorsys compileall compression concurrent configparser
    contextlib contextvars copy copyreg cprofile crypt csv ctypes curses dataclasses
    datetime dbm decimal difflib dis distutils doctest email encodings ensurepip enum errno
    faulthandler fcntl filecmp fileinput fnmatch fractions ftplib functools gc genericpath
    getopt getpass gettext glob graphlib grp gzip hashlib heapq hmac html http idlelib
    imaplib imghdr imp importlib inspect io ipaddress itertools json keyword lib2to3
    linecache locale logging lzma mailbox mailcap marshal math mimetypes mmap modulefinder
    msilib msvcrt multiprocessing netrc nis nntplib nt ntpath nturl2path numbers numpy
    opcode operator optparse os ossaudiodev pathlib pdb pickle pickletools pipes pkgutil
    platform plistlib poplib posix posixpath pprint profile pstats pty pwd py_compile pyclbr
    pydoc pydoc_data pyexpat queue quopri random re readline reprlib resource rlcompleter
    runpy sched secrets select selectors shelve shlex shutil signal site sitecustomize smtpd
    smtplib sndhdr socket socketserver spwd sqlite3 sre_compile sre_constants sre_parse ssl
    stat statistics string stringprep struct subprocess sunau symtable sys sysconfig syslog
    tabnanny tarfile telnetlib tempfile termios textwrap this threading time timeit tkinter
    token tokenize tomllib trace traceback tracemalloc tty turtle turtledemo types typing
    unicodedata unittest urllib usercustomize uu uuid venv warnings wave weakref webbrowser
    winreg winsound wsgiref xdrlib xml xmlrpc zipapp zipfile zipimport zlib zoneinfo
"""


#: The standard names a prefix may not be, by language (``"c"``, ``"cpp"``, ``"rust"``,
#: ``"matlab"``, ``"python"``), besides :data:`KEYWORDS` (C++: with their variants, see
#: :func:`reserved`).
RESERVED: Mapping[str, frozenset[str]] = MappingProxyType(
    {
        "c": frozenset(_C_HEADERS.split()),
        "cpp": frozenset(_CPP_GLOBAL_NAMES.split()),
        "rust": frozenset(_RUST_NAMES.split()),
        "matlab": frozenset(_MATLAB_NAMES.split()),
        "python": frozenset(_PYTHON_MODULES.split()),
    }
)


def reserved(name: str, lang: str) -> bool:
    """Whether ``name`` is a keyword (:data:`KEYWORDS`) or a standard name of ``lang``
    (:data:`RESERVED`; in C++ also a variant ``logf``, ``lgammal_r``, ``fopen64`` of one).

    >>> reserved("log", "cpp"), reserved("logf", "cpp"), reserved("log", "c")
    (True, True, False)
    >>> reserved("os", "python"), reserved("arm", "python"), reserved("for", "matlab")
    (True, False, True)
    """
    names = RESERVED[lang]
    if name in KEYWORDS or name in names:
        return True
    if lang != "cpp":
        return False
    for tail in ("", *_OTHER_VARIANTS):
        for variant in ("", *_FLOAT_VARIANTS):
            end = variant + tail
            if end and name.endswith(end) and name[: -len(end)] in names:
                return True
    return False


_ASCII = {
    "θ": "theta",
    "α": "alpha",
    "σ": "sigma",
    "π": "pi",
    "−": "-",
    "–": "-",
    "—": "-",
    "…": "...",
    "√": "sqrt",
    "·": "*",
    "×": "x",
    "²": "^2",
    "ⁿ": "^n",
    "≤": "<=",
    "≥": ">=",
    "→": "->",
    "↔": "<->",
    "±": "+/-",
}


def _ascii(text: str) -> str:
    out = []
    for ch in text:
        if ch in _ASCII:
            out.append(_ASCII[ch])
            continue
        plain = unicodedata.normalize("NFKD", ch).encode("ascii", "ignore").decode()
        out.append(plain if plain else ("?" if ch.isprintable() else " "))
    return "".join(out)


def identifier(
    text: str, *, taken: frozenset[str] | set[str] = frozenset(), limit: int = 40
) -> str:
    """A safe identifier for ``text``: lower-case ASCII words joined by ``_``.

    It starts with a letter (``r_`` is put before a leading digit), is at most
    ``limit`` characters, and differs from every keyword and from ``taken`` (a number
    or a ``_`` is added).

    >>> identifier("2R arm"), identifier(""), identifier("a2", taken={"a2"})
    ('r_2r_arm', 'robot', 'a2_2')
    """
    words = re.findall(r"[a-z0-9]+", _ascii(text).lower())
    name = "_".join(words)[:limit].strip("_") or "robot"
    if not name[0].isalpha():
        name = f"r_{name}"
    if name in KEYWORDS:
        name += "_"
    base, k = name, 2
    while name in taken or name in KEYWORDS:
        name = f"{base}_{k}"
        k += 1
    return name


_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*")


def checked_name(text: str) -> str:
    """``text`` when it is a name (an ASCII letter, then letters, digits and ``_``), else a
    :class:`~dhsym.errors.DHError` saying why: a prefix names functions and files, so it is
    never a path (``/``, ``..``, absolute) and never starts with a digit.

    >>> checked_name("puma")
    'puma'
    >>> checked_name("../../escaped")
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: prefix '../../escaped' is not a name: ...
    """
    if _NAME.fullmatch(text):
        return text
    why = (
        "a path"
        if ("/" in text or "\\" in text or ".." in text)
        else "starts with a digit"
        if text[:1].isdigit()
        else "empty"
        if not text
        else "has characters other than letters, digits and _"
    )
    raise DHError(
        f"prefix {text!r} is not a name: it is {why}. The prefix names the functions and "
        "files (<prefix>_fk, <prefix>.h): an ASCII letter, then letters, digits and _ "
        "(the folder is given apart, with -o)"
    )


def prefix(text: str | None, lang: str, *, default: str = "robot") -> str:
    """The prefix of the code exported in ``lang``: ``text`` (a name, see
    :func:`checked_name`), or else ``default`` (the robot's name) made an identifier.

    Lower case, at most 40 characters; a prefix that is a keyword of any target language
    or a standard name of ``lang`` (:func:`reserved`: a C header, a C library function in
    C++, a Rust primitive type or crate, a Python standard module) gets a ``_`` at the end,
    never refused: ``log`` is ``log_`` in C++, ``os`` is ``os_`` in Python.

    >>> prefix("Puma", "c"), prefix("log", "cpp"), prefix("log", "c"), prefix("os", "python")
    ('puma', 'log_', 'log', 'os_')
    >>> prefix(None, "c", default="PUMA 560"), prefix("class", "rust")
    ('puma_560', 'class_')
    """
    name = identifier(checked_name(text) if text is not None else default)
    return name + "_" if reserved(name, lang) else name


def comment_lines(text: str) -> list[str]:
    """``text`` as lines safe inside a comment of every target language.

    Printable ASCII only; ``*/`` and ``/*`` (C block comments), ``??`` (trigraphs), a
    backslash (line splices), ``%{`` and ``%}`` (Octave block comments) are broken
    apart; each line of ``text`` is one line (the caller prefixes each).

    >>> comment_lines("a\\\\\\nb */")
    ['a/', 'b * /']
    """
    lines = []
    for raw in _ascii(text).splitlines() or [""]:
        line = "".join(ch if " " <= ch <= "~" else " " for ch in raw)
        line = line.replace("\\", "/")
        for bad, good in (("*/", "* /"), ("/*", "/ *"), ("??", "? ?"), ("%{", "% {")):
            while bad in line:
                line = line.replace(bad, good)
        line = line.replace("%}", "% }")
        lines.append(line.rstrip())
    return lines
