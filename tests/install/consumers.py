#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""consumers.py - builds consumer.c the three ways a user adopts cylray, and runs it;
and consumer_embree.c against the Embree adapter, where it was built.

Usage: consumers.py pkgconfig|cmake|subproject|embree-pkgconfig|embree-cmake
(the rest comes from the environment
that tests/install/meson.build sets: CYLRAY_SOURCE_ROOT, CYLRAY_BUILD_ROOT, CYLRAY_WORK,
CYLRAY_PREFIX, CYLRAY_LIBDIR, CYLRAY_DEFAULT_LIBRARY, CYLRAY_MESON, CC)

  pkgconfig   meson install into a staging directory, then compile with the flags
              `pkg-config cylray` gives for that tree, and run against its library
  cmake       the same staging, then a CMake project with find_package(cylray): as
              it comes (the shared library, where one is installed) and with
              cylray_USE_STATIC=ON where the static one is (the program must then not
              need libcylray at run time)
  subproject  a meson project with this source tree as subprojects/cylray
  embree-pkgconfig, embree-cmake
              consumer_embree.c the same two ways, through `pkg-config cylray_embree`
              and the CMake target cylray::cylray_embree

Exits 77 (skipped) when the tool a way needs (pkg-config, cmake, meson) is missing.
"""
import os
import shlex
import shutil
import subprocess
import sys

SKIP = 77
HERE = os.path.dirname(os.path.abspath(__file__))


class Failed(Exception):
    pass


def run(cmd, env=None, cwd=None):
    """Runs cmd, echoing it; returns its stdout. Raises Failed with its output."""
    print('+', ' '.join(shlex.quote(c) for c in cmd), flush=True)
    p = subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True)
    if p.returncode != 0:
        raise Failed(f'{cmd[0]} exited {p.returncode}\n{p.stdout}{p.stderr}')
    return p.stdout


def cc():
    """The build's C compiler (CC; CMake and meson read it from there too)."""
    return shlex.split(os.environ.get('CC', 'cc'))


def fresh(path):
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return path


def stage(work):
    """meson install of this build into <work>/destdir; returns (destdir, prefix dir)."""
    destdir = fresh(os.path.join(work, 'destdir'))
    run([*shlex.split(os.environ['CYLRAY_MESON']), 'install', '-C',
         os.environ['CYLRAY_BUILD_ROOT'], '--no-rebuild', '--quiet', '--destdir', destdir])
    prefix = os.environ['CYLRAY_PREFIX']
    return destdir, destdir + prefix


def run_consumer(exe, library_path=None, path_name=None):
    """Runs a consumer with no library path but library_path: meson test points
    LD_LIBRARY_PATH at the build tree, and the consumer must find the library it was
    built against. path_name: the kernel path that library must choose."""
    env = dict(os.environ)
    env.pop('LD_LIBRARY_PATH', None)
    if library_path:
        env['LD_LIBRARY_PATH'] = library_path
    out = run([exe], env=env)
    print(out, end='')
    if 'as expected' not in out:
        raise Failed(f'{exe} did not report its result')
    if path_name and f' {path_name} path' not in out:
        raise Failed(f'{exe} did not use a library with only the {path_name} path')


def libdir_of(root):
    libdir = os.environ['CYLRAY_LIBDIR']
    return libdir if os.path.isabs(libdir) else os.path.join(root, libdir)


def way_pkgconfig(work, package='cylray', source='consumer.c'):
    pkg_config = shutil.which('pkg-config') or shutil.which('pkgconf')
    if not pkg_config:
        print('pkg-config not found; skipped')
        return SKIP
    _, root = stage(work)
    env = dict(os.environ)
    # Only the staged tree, its prefix moved under the staging directory: by the prefix
    # variable, not PKG_CONFIG_SYSROOT_DIR, which would move an Embree's own paths (from
    # an install prefix of its own, outside the staged tree) too.
    env['PKG_CONFIG_LIBDIR'] = os.path.join(libdir_of(root), 'pkgconfig')
    env.pop('PKG_CONFIG_PATH', None)
    env.pop('PKG_CONFIG_SYSROOT_DIR', None)
    # With only the static library installed, -lcylray needs its private libraries too.
    static = ['--static'] if os.environ['CYLRAY_DEFAULT_LIBRARY'] == 'static' else []
    flags = shlex.split(run([pkg_config, '--define-variable=prefix=' + root, '--cflags',
                             '--libs', *static, package], env=env))
    exe = os.path.join(work, source[:-2] + '-pkgconfig')
    run([*cc(), '-std=c11', os.path.join(HERE, source), '-o', exe, *flags, '-lm'])
    # An Embree from a prefix of its own is the user's to put on the library path (its
    # pkg-config flags name the directory to link with, not an rpath).
    paths = [libdir_of(root)]
    if package == 'cylray_embree' and os.environ.get('CYLRAY_EMBREE_LIBDIR'):
        paths.append(os.environ['CYLRAY_EMBREE_LIBDIR'])
    run_consumer(exe, library_path=os.pathsep.join(paths))
    return 0


def needs_libcylray(exe):
    """True when exe names a libcylray among the shared objects it needs (ELF)."""
    readelf = shutil.which('readelf')
    if not readelf:
        return None
    return 'libcylray' in run([readelf, '-d', exe])


def way_cmake(work, project='cmake', exe_name='consumer'):
    cmake = shutil.which('cmake')
    if not cmake:
        print('cmake not found; skipped')
        return SKIP
    _, root = stage(work)
    generator = ['-G', 'Ninja'] if shutil.which('ninja') else []
    installed = os.environ['CYLRAY_DEFAULT_LIBRARY']
    # cylray::cylray is the shared library where one is installed; with
    # cylray_USE_STATIC (where the static one is) it is the static library.
    legs = [('default', [], installed != 'static')]
    if installed != 'shared':
        legs.append(('static', ['-Dcylray_USE_STATIC=ON'], False))
    for leg, extra, want_dynamic in legs:
        build = fresh(os.path.join(work, 'cmake-' + leg))
        run([cmake, *generator, '-S', os.path.join(HERE, project), '-B', build,
             '-DCMAKE_PREFIX_PATH=' + root, '-DCMAKE_BUILD_TYPE=Release',
             '-DCYLRAY_WANT=' + '.'.join(os.environ['CYLRAY_VERSION'].split('.')[:2]), *extra])
        run([cmake, '--build', build])
        exe = os.path.join(build, exe_name)
        dynamic = needs_libcylray(exe)
        if dynamic is not None and dynamic != want_dynamic:
            raise Failed(f'the {leg} consumer {"needs" if dynamic else "does not need"} '
                         'libcylray at run time')
        # CMake gives the shared consumer an rpath into the staged tree: no library path.
        run_consumer(exe)
    return 0


def way_subproject(work):
    meson = shlex.split(os.environ['CYLRAY_MESON'])
    project = fresh(os.path.join(work, 'project'))
    shutil.copy(os.path.join(HERE, 'subproject', 'meson.build'), project)
    shutil.copy(os.path.join(HERE, 'consumer.c'), project)
    os.makedirs(os.path.join(project, 'subprojects'))
    os.symlink(os.environ['CYLRAY_SOURCE_ROOT'], os.path.join(project, 'subprojects', 'cylray'))
    build = os.path.join(project, 'build')
    # The scalar path alone: the subproject mechanism is what is tested here, and the
    # SIMD kernels would only make the build longer.
    isas = [f'-Dcylray:{isa}=disabled' for isa in ('sse41', 'avx2', 'avx512', 'neon')]
    run([*meson, 'setup', build, project, '--force-fallback-for=cylray', *isas])
    run([*meson, 'compile', '-C', build])
    run_consumer(os.path.join(build, 'consumer'), path_name='scalar')
    return 0


def main():
    ways = {'pkgconfig': way_pkgconfig, 'cmake': way_cmake, 'subproject': way_subproject,
            'embree-pkgconfig': lambda w: way_pkgconfig(w, 'cylray_embree', 'consumer_embree.c'),
            'embree-cmake': lambda w: way_cmake(w, 'cmake_embree', 'consumer_embree')}
    if len(sys.argv) != 2 or sys.argv[1] not in ways:
        print(__doc__)
        return 2
    work = fresh(os.path.join(os.environ['CYLRAY_WORK'], sys.argv[1]))
    try:
        return ways[sys.argv[1]](work)
    except Failed as e:
        print(f'consumers.py {sys.argv[1]}: FAILED: {e}')
        return 1


if __name__ == '__main__':
    sys.exit(main())
