# One-off converter: Robotics Library mdl.xml -> URDF (fixed transforms become fixed joints).
# With a third argument MESH_DIR, bodies body0..body6 get the scenario's link meshes
# MESH_DIR/link0.wrl..link6.wrl as collision geometry (RL body geometry is in the body frame;
# robot-*.wrl places linkN at bodyN's frame); without it the URDF has no collision geometry.
import math, sys, xml.etree.ElementTree as ET
src, name = sys.argv[1], sys.argv[2]
mesh_dir = sys.argv[3] if len(sys.argv) > 3 else None
m = ET.parse(src).getroot().find('model')
num = lambda e, tag, d=0.0: float(e.find(tag).text) if e is not None and e.find(tag) is not None else d
out = ['<?xml version="1.0"?>',
       '<!-- Converted from bimanual-assembly-scenario/%s (Robotics Library kinematics,' % src.split('/')[-1],
       '     gaschler/bimanual-assembly-scenario) by a one-off script: every RL frame/body is a link,',
       '     every RL <fixed> a fixed joint (rpy = RL rotation x, y, z), angles converted to radians.',
       '     The RL <world> translation is the robot base pose in the scene, not part of this file.' +
       ('\n     Collision geometry of body0..body6: the scenario\'s robots/link0.wrl..link6.wrl.'
        if mesh_dir else '') + ' -->',
       '<robot name="%s">' % name]
links = [e.get('id') for e in m if e.tag in ('world', 'body', 'frame')]
link_meshes = {'body%d' % i: '%s/link%d.wrl' % (mesh_dir, i) for i in range(7)} if mesh_dir else {}
for l in links:
    if l in link_meshes:
        out.append('  <link name="%s">' % l)
        out.append('    <collision><geometry><mesh filename="%s"/></geometry></collision>' % link_meshes[l])
        out.append('  </link>')
    else:
        out.append('  <link name="%s"/>' % l)
for e in m:
    if e.tag not in ('fixed', 'revolute', 'prismatic'): continue
    a = e.find('frame/a').get('idref'); b = e.find('frame/b').get('idref')
    if e.tag == 'fixed':
        r = e.find('rotation'); t = e.find('translation')
        rpy = [math.radians(num(r, k)) for k in 'xyz']; xyz = [num(t, k) for k in 'xyz']
        out.append('  <joint name="%s" type="fixed">' % e.get('id'))
        out.append('    <origin xyz="%s" rpy="%s"/>' % (' '.join('%.17g' % v for v in xyz), ' '.join('%.17g' % v for v in rpy)))
    else:
        ax = e.find('axis'); axis = [num(ax, 'x'), num(ax, 'y'), num(ax, 'z', 1.0)] if ax is not None else [0, 0, 1]
        scale = math.pi / 180 if e.tag == 'revolute' else 1.0
        out.append('  <joint name="%s" type="%s">' % (e.get('id'), e.tag))
        out.append('    <axis xyz="%s"/>' % ' '.join('%g' % v for v in axis))
        out.append('    <limit lower="%.17g" upper="%.17g" velocity="%.17g" effort="0"/>' % (
            num(e, 'min') * scale, num(e, 'max') * scale, num(e, 'speed') * scale))
    out.append('    <parent link="%s"/>\n    <child link="%s"/>\n  </joint>' % (a, b))
out.append('</robot>')
print('\n'.join(out))
